#include "bim/optimizer/agraph_optimizer.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

const std::string kPlans = std::string(ISG_SOURCE_DIR) + "/worlds/plans/";
constexpr double kMillimetre = 1e-3;

// Perturbs nodes with Gaussian noise: planes by `angle` rad and `distance` m, centres by `shift` m.
void perturb(AGraphState& state, std::mt19937& rng, double angle, double distance, double shift,
             bool planes) {
  std::normal_distribution<double> n(0.0, 1.0);
  PlaneManifold manifold;
  if (planes) {
    for (auto& p : state.planes) {
      const Eigen::Vector3d step(angle * n(rng), angle * n(rng), distance * n(rng));
      Eigen::Vector4d moved;
      manifold.Plus(p.data(), step.data(), moved.data());
      p = moved;
    }
  }
  for (auto& w : state.walls) w += shift * Eigen::Vector3d(n(rng), n(rng), n(rng));
  for (auto& r : state.rooms) r += shift * Eigen::Vector2d(n(rng), n(rng));
  for (auto& d : state.doorways) d.head<2>() += shift * Eigen::Vector2d(n(rng), n(rng));
}

// The largest distance of any node from the plan's value (planes: distance and angle).
struct Deviation {
  double position = 0.0;  // m
  double plane_distance = 0.0;
  double plane_angle = 0.0;
};

Deviation deviation(const AGraphState& state) {
  const AGraph& g = state.graph();
  Deviation out;
  for (std::size_t i = 0; i < g.surfaces.size(); ++i) {
    const Plane p = toPlane(state.planes[i]);
    out.plane_distance = std::max(out.plane_distance, std::abs(p.d - g.surfaces[i].plane.d));
    out.plane_angle =
        std::max(out.plane_angle,
                 std::acos(std::clamp(p.normal.dot(g.surfaces[i].plane.normal), -1.0, 1.0)));
  }
  for (std::size_t i = 0; i < g.walls.size(); ++i) {
    out.position = std::max(out.position, (state.walls[i] - g.walls[i].centre).norm());
  }
  for (std::size_t i = 0; i < g.rooms.size(); ++i) {
    out.position = std::max(out.position, (state.rooms[i] - g.rooms[i].centre).norm());
  }
  for (std::size_t i = 0; i < g.doorways.size(); ++i) {
    out.position = std::max(out.position, (state.doorways[i] - g.doorways[i].position).norm());
  }
  return out;
}

class AGraphRecovery : public ::testing::TestWithParam<std::string> {};

TEST_P(AGraphRecovery, AtThePlanEveryFactorIsZero) {
  const AGraph graph = buildAGraph(loadPlan(kPlans + GetParam() + ".json"));
  AGraphState state(graph);
  EXPECT_LT(state.optimize(), 1e-16);
  EXPECT_LT(deviation(state).position, 1e-9);
}

TEST_P(AGraphRecovery, EveryNodePerturbedReturnsToThePlan) {
  const AGraph graph = buildAGraph(loadPlan(kPlans + GetParam() + ".json"));
  AGraphState state(graph);
  std::mt19937 rng(42);
  perturb(state, rng, 0.03, 0.1, 0.2, /*planes=*/true);
  const Deviation before = deviation(state);
  EXPECT_GT(before.position, 0.2);
  state.optimize();
  const Deviation after = deviation(state);
  EXPECT_LT(after.position, kMillimetre);
  EXPECT_LT(after.plane_distance, kMillimetre);
  EXPECT_LT(after.plane_angle, kMillimetre);
}

TEST_P(AGraphRecovery, StructuralFactorsAloneRestoreWallsRoomsAndDoorways) {
  // Planes held at the plan, no priors: only the wall, room and doorway factors act.
  const AGraph graph = buildAGraph(loadPlan(kPlans + GetParam() + ".json"));
  AGraphState state(graph);
  std::mt19937 rng(7);
  perturb(state, rng, 0.0, 0.0, 0.3, /*planes=*/false);
  state.optimize({}, /*plane_priors=*/false, /*fix_planes=*/true);
  // Polygon rooms have no room factor: only their doorways tie them, so they may not return.
  const AGraph& g = state.graph();
  for (std::size_t i = 0; i < g.walls.size(); ++i) {
    EXPECT_LT((state.walls[i] - g.walls[i].centre).norm(), kMillimetre) << g.walls[i].id;
  }
  for (std::size_t i = 0; i < g.rooms.size(); ++i) {
    if (g.rooms[i].kind == RoomKind::kPolygon) continue;
    EXPECT_LT((state.rooms[i] - g.rooms[i].centre).norm(), kMillimetre) << g.rooms[i].id;
  }
  for (std::size_t i = 0; i < g.doorways.size(); ++i) {
    EXPECT_LT((state.doorways[i] - g.doorways[i].position).norm(), kMillimetre) << g.doorways[i].id;
  }
}

INSTANTIATE_TEST_SUITE_P(ReferencePlans, AGraphRecovery,
                         ::testing::Values("d1", "d2", "d3", "d4", "d5", "d6"));

TEST(AGraphRecoveryLarge, TwoHundredRoomGrid) {
  const Plan plan = testing::parsePlanJson(makeGridPlan({}));
  const AGraph graph = buildAGraph(plan);
  AGraphState state(graph);
  std::mt19937 rng(3);
  perturb(state, rng, 0.02, 0.05, 0.1, true);
  state.optimize();
  const Deviation after = deviation(state);
  EXPECT_LT(after.position, kMillimetre);
  EXPECT_LT(after.plane_distance, kMillimetre);
}

}  // namespace
}  // namespace isg::bim
