#include "run/localizer_registry.hpp"

#include <gtest/gtest.h>

#include "run/builtin_methods.hpp"

namespace isg::run {
namespace {

TEST(LocalizerRegistry, BuiltinMethodsInTableOrder) {
  const LocalizerRegistry registry = builtinMethods();
  EXPECT_EQ(registry.names(),
            (std::vector<std::string>{"is-graphs", "amcl", "ndt-ukf", "s-graph", "odometry"}));
  EXPECT_TRUE(registry.find("is-graphs")->needs_plan);
  EXPECT_TRUE(registry.find("amcl")->needs_plan);
  EXPECT_FALSE(registry.find("amcl")->given_start);
  EXPECT_TRUE(registry.find("ndt-ukf")->given_start);
  EXPECT_FALSE(registry.find("s-graph")->needs_plan);
  EXPECT_TRUE(registry.find("s-graph")->slam_only);
  EXPECT_TRUE(registry.find("odometry")->given_start);
  EXPECT_EQ(registry.find("cartographer"), nullptr);
  EXPECT_NE(registry.help().find("  s-graph: "), std::string::npos);
  EXPECT_NE(registry.help().find("  odometry (or dead-reckoning): "), std::string::npos);
}

// The old name of a renamed method still works on the command line and in old run folders.
TEST(LocalizerRegistry, AnAliasFindsTheRenamedMethod) {
  const LocalizerRegistry registry = builtinMethods();
  EXPECT_EQ(registry.find("dead-reckoning"), registry.find("odometry"));
  EXPECT_EQ(registry.canonical("dead-reckoning"), "odometry");
  EXPECT_EQ(registry.canonical("someone-elses"), "someone-elses");
  const auto accepted = registry.acceptedNames();
  EXPECT_NE(std::find(accepted.begin(), accepted.end(), "dead-reckoning"), accepted.end());
  LocalizerRegistry mine;
  addDeadReckoning(mine);
  EXPECT_THROW(mine.add({.name = "dead-reckoning",
                         .make =
                             [](const LocalizerContext&) {
                               return std::make_unique<slam::DeadReckoning>();
                             }}),
               std::invalid_argument);
}

TEST(LocalizerRegistry, MakesWhatTheContextAllows) {
  const LocalizerRegistry registry = builtinMethods();
  LocalizerContext context;
  EXPECT_THROW(registry.make("is-graphs", context), std::invalid_argument);       // no plan
  EXPECT_THROW(registry.make("dead-reckoning", context), std::invalid_argument);  // no start
  EXPECT_THROW(registry.make("amcl", context), std::invalid_argument);            // no plan
  EXPECT_THROW(registry.make("nonsense", context), std::invalid_argument);
  EXPECT_EQ(registry.make("s-graph", context)->name(), "s-graph");
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.translation() = Eigen::Vector3d(2, 3, 0);
  context.start_B_T_M = start;
  const auto dead_reckoning = registry.make("dead-reckoning", context);
  EXPECT_EQ(dead_reckoning->name(), "odometry");
  ASSERT_TRUE(dead_reckoning->mapInPlan());
  EXPECT_TRUE(dead_reckoning->mapInPlan()->isApprox(start));
  EXPECT_FALSE(dead_reckoning->searchStatus());
  EXPECT_FALSE(dead_reckoning->mapDiagnostics());
}

// Options are checked without a world (a sweep checks its suite before any run), by each
// method's own reader; a method that reads none refuses every key.
TEST(LocalizerRegistry, ChecksOptionsWithoutAWorld) {
  const LocalizerRegistry registry = builtinMethods();
  EXPECT_NO_THROW(registry.checkOptions("amcl", {{"particles", "5000"}, {"alpha_fast", "0.1"}}));
  EXPECT_NO_THROW(registry.checkOptions("ndt-ukf", {{"start_error", "0"}}));
  EXPECT_NO_THROW(registry.checkOptions("is-graphs", {}));
  const auto message = [&](const std::string& method,
                           const std::map<std::string, std::string>& options) {
    try {
      registry.checkOptions(method, options);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("amcl", {{"particles", "0"}}),
            "particles=0: amcl's particles must be a number in [1, 1e+07]");
  EXPECT_EQ(message("ndt-ukf", {{"wall_band", "x"}}),
            "wall_band=x: ndt-ukf's wall_band must be a number in [0, 10]");
  EXPECT_EQ(message("dead-reckoning", {{"particles", "10"}}),
            "particles=10: odometry has no option particles (it has none)");
  EXPECT_EQ(message("is-graphs", {{"threshold", "1"}}),
            "threshold=1: is-graphs has no option threshold (it has none)");
  EXPECT_EQ(message("nonsense", {}), "unknown method nonsense");
  // make() checks them too.
  LocalizerContext context;
  context.options = {{"speed", "2"}};
  EXPECT_THROW(registry.make("s-graph", context), std::invalid_argument);
}

TEST(LocalizerRegistry, ANewMethodAddsItselfOnce) {
  LocalizerRegistry registry;
  addSGraph(registry);
  EXPECT_THROW(addSGraph(registry), std::invalid_argument);
  EXPECT_THROW(registry.add({.name = "empty", .summary = "no factory"}), std::invalid_argument);
  registry.add(
      {.name = "still", .summary = "stands at the origin", .make = [](const LocalizerContext&) {
         return std::make_unique<slam::DeadReckoning>();
       }});
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"s-graph", "still"}));
}

}  // namespace
}  // namespace isg::run
