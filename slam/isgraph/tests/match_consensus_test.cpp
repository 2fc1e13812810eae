// Walls built off the plan, in matching: adequacy reads an S-plane near a surface as that wall
// built off, and the walls' vote moves an answer that sits on walls built off the same way back to
// where the walls built as planned are.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <string>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/tests/synthetic_sgraph.hpp"

namespace isg::slam {
namespace {

bim::AGraph d1AGraph() {
  return bim::buildAGraph(bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json"));
}

// A 3 × 6 grid of rooms: many walls facing each way.
bim::AGraph consensusGrid() {
  bim::GridPlanSpec spec;
  spec.rows = 3;
  spec.cols = 6;
  spec.size_seed = 1;
  const common::JsonSource source{"grid.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(bim::makeGridPlan(spec), "", source)));
}

std::vector<int> allRooms(const bim::AGraph& graph) {
  std::vector<int> all;
  for (int r = 0; r < int(graph.rooms.size()); ++r) all.push_back(r);
  return all;
}

// Moves an S-plane by `shift` given in B (the cut's truth maps M to B).
void moveInB(MatchPlane& plane, const Eigen::Vector2d& shift, const Eigen::Vector3d& B_T_M) {
  const Eigen::Vector2d in_M = Eigen::Rotation2Dd(-B_T_M.z()) * shift;
  plane.start += in_M;
  plane.end += in_M;
  plane.plane =
      bim::Plane::throughPoint(plane.plane.normal, {plane.start.x(), plane.start.y(), 1.0});
}

// At the truth, a wall moved 0.25 m along its normal is unexplained (beyond the 0.15 m of
// matching) but lies as a wall built off would: adequacy does not count it. One moved 0.6 m, beyond
// the 0.4 m of a wall built off, counts.
TEST(Consensus, AdequacyReadsAWallNearItsSurfaceAsBuiltOff) {
  const bim::AGraph graph = d1AGraph();
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(2);
  const Eigen::Vector3d truth(3.0, -2.0, 0.7);
  auto cut = testing::cutSGraph(graph, allRooms(graph), truth, rng, 0.0);
  const double min_length = matcher.options().min_plane_length;
  // The first two evidence planes: one moved 0.25 m, one 0.6 m.
  std::vector<int> moved;
  for (int i = 0; i < int(cut.input.planes.size()) && moved.size() < 2; ++i) {
    if (cut.input.planes[i].length() >= min_length) moved.push_back(i);
  }
  ASSERT_EQ(moved.size(), 2u);
  double evidence = 0.0;
  for (const auto& p : cut.input.planes) {
    if (p.length() >= min_length) evidence += p.length();
  }
  MatchPlane& near = cut.input.planes[moved[0]];
  MatchPlane& far = cut.input.planes[moved[1]];
  const auto& near_surface = graph.surfaces[cut.a_surface_of_s_plane[moved[0]]];
  const auto& far_surface = graph.surfaces[cut.a_surface_of_s_plane[moved[1]]];
  moveInB(near, 0.25 * near_surface.plane.normal.head<2>(), truth);
  moveInB(far, 0.6 * far_surface.plane.normal.head<2>(), truth);
  const Verification v = matcher.verify(cut.input, truth);
  EXPECT_NEAR(v.unexplained_length, near.length() + far.length(), 1e-9);
  EXPECT_NEAR(v.built_off_length, near.length(), 1e-9);
  EXPECT_NEAR(v.unexplainedShare(), far.length() / evidence, 1e-9);
}

// Two plan walls facing one way built 0.25 m off the same way. An answer 0.25 m off along their
// normal puts them on their surfaces and leaves every other wall facing that way off by 0.25 m; the
// walls' vote moves it back to the truth. At the truth the two are outvoted: it stays.
TEST(Consensus, TheWallsVoteAnAnswerOnWallsBuiltOffBackToTheTruth) {
  const bim::AGraph graph = consensusGrid();
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(5);
  const Eigen::Vector3d truth(-4.0, 6.0, -1.1);
  auto cut = testing::cutSGraph(graph, allRooms(graph), truth, rng, 0.0);
  // Along the direction most plan walls face (±): the answer's error, in B, is delta.
  auto wallsFacing = [&](const Eigen::Vector2d& n) {
    std::map<std::string, int> facing;  // plan wall → its S-planes
    for (int i = 0; i < int(cut.input.planes.size()); ++i) {
      const auto& s = graph.surfaces[cut.a_surface_of_s_plane[i]];
      if (std::abs(s.plane.normal.head<2>().dot(n)) > 0.99) ++facing[s.wall];
    }
    return facing;
  };
  const Eigen::Vector2d n =
      wallsFacing(Eigen::Vector2d::UnitX()).size() >= wallsFacing(Eigen::Vector2d::UnitY()).size()
          ? Eigen::Vector2d::UnitX()
          : Eigen::Vector2d::UnitY();
  const Eigen::Vector2d delta = 0.25 * n;
  // The first two of those walls are built off by −delta: under the answer off by delta they land
  // on their surfaces.
  const std::map<std::string, int> facing = wallsFacing(n);
  ASSERT_GE(facing.size(), 6u) << "the grid has fewer walls facing one way than this test needs";
  std::set<std::string> built_off;
  for (const auto& [wall, planes] : facing) {
    if (built_off.size() < 2) built_off.insert(wall);
  }
  for (int i = 0; i < int(cut.input.planes.size()); ++i) {
    if (built_off.count(graph.surfaces[cut.a_surface_of_s_plane[i]].wall)) {
      moveInB(cut.input.planes[i], -delta, truth);
    }
  }
  const Eigen::Vector3d off(truth.x() + delta.x(), truth.y() + delta.y(), truth.z());
  const double at_truth = matcher.wallsAgreeing(cut.input, truth);
  const double at_off = matcher.wallsAgreeing(cut.input, off);
  EXPECT_GE(at_truth, at_off + matcher.options().consensus_min_walls);
  const Verification moved = matcher.consensus(cut.input, matcher.verify(cut.input, off));
  EXPECT_NEAR((moved.x_y_yaw.head<2>() - truth.head<2>()).norm(), 0.0, 0.02);
  EXPECT_NEAR(moved.x_y_yaw.z(), truth.z(), 1e-3);
  const Verification stays = matcher.consensus(cut.input, matcher.verify(cut.input, truth));
  EXPECT_EQ(stays.x_y_yaw, truth);
}

}  // namespace
}  // namespace isg::slam
