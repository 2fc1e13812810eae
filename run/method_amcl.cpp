#include "run/builtin_methods.hpp"
#include "run/method_options.hpp"
#include "slam/baselines/amcl_localizer.hpp"

namespace isg::run {

namespace {

// The filter's settings from --method-option: nav2's defaults where a key is not given.
slam::AmclOptions amclOptions(MethodOptions& given) {
  slam::AmclOptions options;
  auto& f = options.filter;
  f.max_particles = given.integer("particles", f.max_particles, 1, 10000000);
  f.min_particles = given.integer("min_particles", std::min(f.min_particles, f.max_particles), 1,
                                  f.max_particles);
  f.alpha_slow = given.number("alpha_slow", f.alpha_slow, 0.0, 1.0);
  f.alpha_fast = given.number("alpha_fast", f.alpha_fast, 0.0, 1.0);
  options.update_min_d = given.number("update_min_d", options.update_min_d, 0.0, 100.0);
  options.update_min_a = given.number("update_min_a", options.update_min_a, 0.0, 7.0);
  given.finish();
  return options;
}

}  // namespace

void addAmcl(LocalizerRegistry& registry) {
  registry.add(
      {.name = "amcl",
       .summary = "2D Monte Carlo localization as ROS AMCL (KLD sampling, likelihood field of the "
                  "plan, augmented MCL), global start, nav2's defaults with the ROS wiki's "
                  "recovery alphas; options particles, min_particles, alpha_slow, alpha_fast, "
                  "update_min_d, update_min_a "
                  "(docs/baselines.md)",
       .needs_plan = true,
       .make =
           [](const LocalizerContext& c) {
             MethodOptions given(c.options, "amcl");
             return std::make_unique<slam::AmclLocalizer>(*c.plan, c.level, c.R_T_L,
                                                          amclOptions(given), c.seed);
           },
       .check_options =
           [](const auto& options) {
             MethodOptions given(options, "amcl");
             (void)amclOptions(given);
             return given.effective();
           }});
}

}  // namespace isg::run
