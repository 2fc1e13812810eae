#include <random>

#include "run/builtin_methods.hpp"
#include "run/method_options.hpp"
#include "slam/baselines/ndt_ukf_localizer.hpp"

namespace isg::run {

namespace {

// The method's settings: how far its start is moved, and the tracker's own.
struct NdtUkfSettings {
  double start_error = 0.3;          // m
  double start_yaw_error_deg = 5.0;  // degrees
  slam::NdtUkfOptions tracker;
};

NdtUkfSettings ndtUkfSettings(MethodOptions& given) {
  NdtUkfSettings s;
  s.start_error = given.number("start_error", s.start_error, 0.0, 100.0);
  s.start_yaw_error_deg = given.number("start_yaw_error_deg", s.start_yaw_error_deg, 0.0, 180.0);
  auto& t = s.tracker;
  t.scan_voxel = given.number("scan_voxel", t.scan_voxel, 0.01, 10.0);
  t.ndt_resolution = given.number("ndt_resolution", t.ndt_resolution, 0.1, 10.0);
  t.map_relief = given.number("map_relief", t.map_relief, 0.0, 1.0);
  t.wall_band = given.number("wall_band", t.wall_band, 0.0, 10.0);
  given.finish();
  return s;
}

}  // namespace

void addNdtUkf(LocalizerRegistry& registry) {
  registry.add(
      {.name = "ndt-ukf",
       .summary = "hdl_localization's design: PCL NDT against a cloud of the plan's walls, an "
                  "unscented Kalman filter with the odometry; a tracker started from the true "
                  "start moved start_error (0.3 m) in a direction drawn from the seed and turned "
                  "start_yaw_error_deg (5°); options those two, scan_voxel (0.4 m), "
                  "ndt_resolution (1 m), map_relief (0.01 m), wall_band (0.2 m) "
                  "(docs/baselines.md)",
       .needs_plan = true,
       .given_start = true,
       .make =
           [](const LocalizerContext& c) {
             MethodOptions given(c.options, "ndt-ukf");
             const NdtUkfSettings settings = ndtUkfSettings(given);
             // The perturbation: its size is stated, its direction and the turn's sign come from
             // the seed (its own stream, so other draws of the run do not shift it).
             std::mt19937_64 rng(c.seed ^ 0x6e64742d756b66ULL);
             std::uniform_real_distribution<double> unit(0.0, 1.0);
             const double direction = 2.0 * M_PI * unit(rng);
             const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
             // M is the base's frame at the start: the turn is about the start pose.
             Eigen::Isometry3d start = *c.start_B_T_M;
             start.translation() += settings.start_error *
                                    Eigen::Vector3d(std::cos(direction), std::sin(direction), 0);
             start.linear() = Eigen::AngleAxisd(sign * settings.start_yaw_error_deg * M_PI / 180.0,
                                                Eigen::Vector3d::UnitZ())
                                  .toRotationMatrix() *
                              start.linear();
             return std::make_unique<slam::NdtUkfLocalizer>(*c.plan, c.level, c.R_T_L, start,
                                                            settings.tracker);
           },
       .check_options =
           [](const auto& options) {
             MethodOptions given(options, "ndt-ukf");
             (void)ndtUkfSettings(given);
             return given.effective();
           }});
}

}  // namespace isg::run
