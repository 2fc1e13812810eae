#include "run/localizer_registry.hpp"

#include <gtest/gtest.h>

#include "run/builtin_methods.hpp"

namespace isg::run {
namespace {

TEST(LocalizerRegistry, BuiltinMethodsInTableOrder) {
  const LocalizerRegistry registry = builtinMethods();
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"is-graphs", "s-graph", "dead-reckoning"}));
  EXPECT_TRUE(registry.find("is-graphs")->needs_plan);
  EXPECT_FALSE(registry.find("s-graph")->needs_plan);
  EXPECT_TRUE(registry.find("dead-reckoning")->given_start);
  EXPECT_EQ(registry.find("amcl"), nullptr);
  EXPECT_NE(registry.help().find("  s-graph: "), std::string::npos);
}

TEST(LocalizerRegistry, MakesWhatTheContextAllows) {
  const LocalizerRegistry registry = builtinMethods();
  LocalizerContext context;
  EXPECT_THROW(registry.make("is-graphs", context), std::invalid_argument);       // no plan
  EXPECT_THROW(registry.make("dead-reckoning", context), std::invalid_argument);  // no start
  EXPECT_THROW(registry.make("nonsense", context), std::invalid_argument);
  EXPECT_EQ(registry.make("s-graph", context)->name(), "s-graph");
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.translation() = Eigen::Vector3d(2, 3, 0);
  context.start_B_T_M = start;
  const auto dead_reckoning = registry.make("dead-reckoning", context);
  ASSERT_TRUE(dead_reckoning->mapInPlan());
  EXPECT_TRUE(dead_reckoning->mapInPlan()->isApprox(start));
  EXPECT_FALSE(dead_reckoning->searchStatus());
  EXPECT_FALSE(dead_reckoning->mapDiagnostics());
}

TEST(LocalizerRegistry, ANewMethodAddsItselfOnce) {
  LocalizerRegistry registry;
  addSGraph(registry);
  EXPECT_THROW(addSGraph(registry), std::invalid_argument);
  EXPECT_THROW(registry.add({"empty", "no factory", false, false, {}}), std::invalid_argument);
  registry.add({"still", "stands at the origin", false, false,
                [](const LocalizerContext&) { return std::make_unique<slam::DeadReckoning>(); }});
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"s-graph", "still"}));
}

}  // namespace
}  // namespace isg::run
