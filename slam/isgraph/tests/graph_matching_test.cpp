#include "slam/isgraph/graph_matching.hpp"

#include <gtest/gtest.h>
#include <numbers>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <set>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "slam/isgraph/tests/synthetic_sgraph.hpp"

namespace isg::slam {
namespace {

bim::AGraph matchingGrid(int rows, int cols, std::uint64_t size_seed) {
  bim::GridPlanSpec spec;
  spec.rows = rows;
  spec.cols = cols;
  spec.size_seed = size_seed;
  const common::JsonSource source{"grid.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(bim::makeGridPlan(spec), "", source)));
}

bim::AGraph referenceAGraph(const std::string& name) {
  const std::string path = std::string(ISG_SOURCE_DIR) + "/worlds/plans/" + name + ".json";
  return bim::buildAGraph(bim::loadPlan(path));
}

double angleError(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * std::numbers::pi));
}

// Every room of `graph` in an S-Graph placed by `truth`, without noise.
testing::CutSGraph everyRoomSeenFrom(const bim::AGraph& graph, const Eigen::Vector3d& truth) {
  std::mt19937_64 rng(1);
  std::vector<int> all;
  for (int r = 0; r < int(graph.rooms.size()); ++r) all.push_back(r);
  return testing::cutSGraph(graph, all, truth, rng, 0.0);
}

// The matched answer is the truth: transform within 5 cm / 0.5°, every room the right one.
void expectRight(const MatchResult& result, const testing::CutSGraph& cut,
                 const Eigen::Vector3d& truth, const std::string& context) {
  const Eigen::Vector2d probe =
      cut.input.rooms.empty() ? Eigen::Vector2d::Zero() : cut.input.rooms[0].centre;
  const Eigen::Vector2d at_truth = Eigen::Rotation2Dd(truth.z()) * probe + truth.head<2>();
  const Eigen::Vector2d at_match =
      Eigen::Rotation2Dd(result.best.x_y_yaw.z()) * probe + result.best.x_y_yaw.head<2>();
  EXPECT_LT((at_truth - at_match).norm(), 0.05) << context;
  EXPECT_LT(angleError(result.best.x_y_yaw.z(), truth.z()), 0.5 * std::numbers::pi / 180.0)
      << context;
  for (const auto& [s, a] : result.best.rooms) {
    EXPECT_EQ(a, cut.a_room_of_s_room[s]) << context << " S-room " << s;
  }
}

struct GridCase {
  int rows, cols;
};

class MatchingOnGrids : public ::testing::TestWithParam<GridCase> {};

// Random B_T_M (any yaw, anywhere), random walks of 1, 4 and 8 rooms: a match, when there is
// one, is always right. Grids of ±20 % rooms have near-repeats (two runs of columns whose walls
// line up within 10–15 cm), so a short walk is often, rightly, ambiguous; after 8 rooms most are
// matched.
TEST_P(MatchingOnGrids, NeverWrongAndMostlyMatchedAfterEightRooms) {
  const auto [rows, cols] = GetParam();
  const bim::AGraph graph = matchingGrid(rows, cols, 17);
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(rows * 1000 + cols);
  int matched_after_eight = 0;
  const int trials = 30;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
    const int start = std::uniform_int_distribution<int>(0, int(graph.rooms.size()) - 1)(rng);
    for (int length : {1, 4, 8}) {
      const auto walk = testing::walkRooms(graph, start, length, rng);
      const auto cut = testing::cutSGraph(graph, walk, truth, rng);
      const MatchResult result = matcher.match(cut.input);
      const std::string context = "trial " + std::to_string(trial) + ", " + std::to_string(length) +
                                  " rooms: " + result.reason;
      if (result.status != MatchStatus::kMatched) continue;
      expectRight(result, cut, truth, context);
      if (length == 8) ++matched_after_eight;
    }
  }
  // Reported, for the record of how often the matcher decides (docs/matching.md).
  std::printf("%dx%d grid: %d of %d walks of 8 rooms matched\n", rows, cols, matched_after_eight,
              trials);
  EXPECT_GE(matched_after_eight, trials * 6 / 10);
}

INSTANTIATE_TEST_SUITE_P(Plans, MatchingOnGrids,
                         ::testing::Values(GridCase{2, 5}, GridCase{5, 10}, GridCase{10, 20}),
                         [](const auto& test_info) {
                           return std::to_string(test_info.param.rows * test_info.param.cols) +
                                  "Rooms";
                         });

// Forty walks of three rooms from random starts under random B_T_M (seed 5), each matched on a
// grid whose sizes repeat every 8 columns and rows: `check(cut, truth, result)` for each.
template <typename Check>
void forEachShortWalkOnARepeatingGrid(const bim::AGraph& graph, Check check) {
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
    const int start = std::uniform_int_distribution<int>(0, int(graph.rooms.size()) - 1)(rng);
    const auto cut =
        testing::cutSGraph(graph, testing::walkRooms(graph, start, 3, rng), truth, rng);
    check(cut, truth, matcher.match(cut.input));
  }
}

// A grid whose sizes repeat every 8 columns and rows is translation-symmetric in places: the
// matcher must say so rather than pick one.
TEST(Matching, RepeatingGridIsNeverMatchedWrong) {
  const bim::AGraph graph = matchingGrid(10, 20, 0);
  int ambiguous = 0;
  forEachShortWalkOnARepeatingGrid(
      graph, [&](const auto& cut, const Eigen::Vector3d& truth, const MatchResult& result) {
        if (result.status == MatchStatus::kMatched) expectRight(result, cut, truth, result.reason);
        if (result.status == MatchStatus::kAmbiguous) ++ambiguous;
      });
  EXPECT_GT(ambiguous, 0);
}

// Where to look, on a grid of many alike rooms: the rooms that would separate the answers are
// named in the plan's order, the first ten and how many more — one line a person reads, not
// every room of the floor.
TEST(Matching, AnAmbiguousReasonNamesTheFirstTenRoomsToLookAt) {
  const bim::AGraph graph = matchingGrid(10, 20, 0);
  int long_lists = 0;
  forEachShortWalkOnARepeatingGrid(graph, [&](const auto&, const Eigen::Vector3d&,
                                              const MatchResult& result) {
    if (result.status != MatchStatus::kAmbiguous) return;
    std::set<std::string> separating;
    for (const auto& c : result.candidates) {
      separating.insert(c.from_best.separating_rooms.begin(), c.from_best.separating_rooms.end());
    }
    std::vector<std::string> named;  // in the plan's order
    for (const auto& room : graph.rooms) {
      if (separating.count(room.id)) named.push_back(room.id);
    }
    if (named.size() <= 10) return;
    ++long_lists;
    std::string expected = "; seeing ";
    for (int i = 0; i < 10; ++i) expected += (i ? ", " : "") + named[i];
    expected += " and " + std::to_string(named.size() - 10) + " more (" +
                std::to_string(named.size()) + " in all) would separate them";
    EXPECT_NE(result.reason.find(expected), std::string::npos) << result.reason;
  });
  EXPECT_GT(long_lists, 0);
}

// The hypotheses verified on a pool's threads: the very same result, whatever the threads.
TEST(Matching, TheSameOnAnyNumberOfThreads) {
  const bim::AGraph graph = matchingGrid(8, 12, 3);
  const GraphMatcher matcher(graph);
  ThreadPool two(2), three(3);
  std::mt19937_64 rng(11);
  int hypotheses = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
    const int start = std::uniform_int_distribution<int>(0, int(graph.rooms.size()) - 1)(rng);
    const auto cut =
        testing::cutSGraph(graph, testing::walkRooms(graph, start, 1 + trial, rng), truth, rng);
    const MatchResult alone = matcher.match(cut.input);
    hypotheses += alone.hypotheses;
    for (ThreadPool* pool : {&two, &three}) {
      const MatchResult shared = matcher.match(cut.input, pool);
      EXPECT_EQ(shared.status, alone.status);
      EXPECT_EQ(shared.reason, alone.reason);
      EXPECT_EQ(shared.best.x_y_yaw, alone.best.x_y_yaw);  // bit for bit
      EXPECT_EQ(shared.best.score, alone.best.score);
      EXPECT_EQ(shared.hypotheses, alone.hypotheses);
      EXPECT_EQ(shared.clusters, alone.clusters);
      ASSERT_EQ(shared.candidates.size(), alone.candidates.size());
      for (std::size_t i = 0; i < alone.candidates.size(); ++i) {
        EXPECT_EQ(shared.candidates[i].answer.x_y_yaw, alone.candidates[i].answer.x_y_yaw);
      }
    }
  }
  EXPECT_GT(hypotheses, 64 * 6);  // more than one item of hypotheses a match, on average
}

// D4's north row (offices R1, R2, R3 with R1 and R3 alike) is symmetric: seen from R1 and R2
// alone the robot could as well be in R3 and R2, turned round. The corridor settles it.
TEST(Matching, MirrorSymmetricPlanIsAmbiguousUntilTheAsymmetricPartIsSeen) {
  const bim::AGraph graph = referenceAGraph("d4");
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(11);
  const int r1 = graph.findRoom("R1"), r2 = graph.findRoom("R2"), r4 = graph.findRoom("R4");
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
    const auto symmetric = testing::cutSGraph(graph, {r1, r2}, truth, rng, 0.01);
    const MatchResult seen_symmetric = matcher.match(symmetric.input);
    EXPECT_EQ(seen_symmetric.status, MatchStatus::kAmbiguous) << seen_symmetric.reason;
    const auto whole = testing::cutSGraph(graph, {r1, r2, r4}, truth, rng, 0.01);
    const MatchResult seen_corridor = matcher.match(whole.input);
    ASSERT_EQ(seen_corridor.status, MatchStatus::kMatched) << seen_corridor.reason;
    expectRight(seen_corridor, whole, truth, seen_corridor.reason);
  }
}

// Each reference plan: walks of three rooms from every room are matched right or not at all.
TEST(Matching, ReferencePlansNeverWrong) {
  for (const char* name : {"d1", "d2", "d3", "d4", "d5", "d6"}) {
    const bim::AGraph graph = referenceAGraph(name);
    const GraphMatcher matcher(graph);
    std::mt19937_64 rng(3);
    int matched = 0;
    for (int start = 0; start < int(graph.rooms.size()); ++start) {
      const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
      const auto cut =
          testing::cutSGraph(graph, testing::walkRooms(graph, start, 3, rng), truth, rng);
      const MatchResult result = matcher.match(cut.input);
      if (result.status != MatchStatus::kMatched) continue;
      ++matched;
      expectRight(result, cut, truth, std::string(name) + ": " + result.reason);
    }
    EXPECT_GT(matched, 0) << name;
  }
}

TEST(Matching, NothingToMatchIsNotYet) {
  const bim::AGraph graph = referenceAGraph("d1");
  const GraphMatcher matcher(graph);
  const MatchResult result = matcher.match({});
  EXPECT_EQ(result.status, MatchStatus::kNotYet);
  EXPECT_EQ(result.reason, "no room in the S-Graph yet");
}

// A room of a size the plan does not have proposes nothing.
TEST(Matching, RoomOfUnknownSizeProposesNothing) {
  const bim::AGraph graph = referenceAGraph("d1");
  const GraphMatcher matcher(graph);
  MatchInput input;
  MatchRoom room;
  room.id = 0;
  room.four_wall = true;
  room.widths = {11.0, 13.0};
  input.rooms.push_back(room);
  const MatchResult result = matcher.match(input);
  EXPECT_EQ(result.status, MatchStatus::kNotYet);
  EXPECT_EQ(result.hypotheses, 0);
  EXPECT_EQ(result.reason, "no S-Graph room or corner fits the plan in kind and size");
}

// An open floor's façade is walls in line with gaps between them (bays between columns): an
// S-plane along it spans the gaps, so a corner's arm reaches as far as the walls in line with its
// own do. Seen from a transform, the S-Graph's corner of the south façade (across its gap) and
// the west wall seeds the truth; with the arm cut at the first wall's end it would seed nothing.
TEST(Matching, ACornerArmReachesAlongTheWallsInLineWithIt) {
  const nlohmann::json plan = {
      {"format", "isg.plan"},
      {"version", 1},
      {"levels",
       {{{"id", "L0"},
         {"height", 3.0},
         {"walls",
          {{{"id", "S1"}, {"start", {0, 0}}, {"end", {6, 0}}, {"thickness", 0.25}},
           {{"id", "S2"}, {"start", {7, 0}}, {"end", {15, 0}}, {"thickness", 0.25}},
           {{"id", "W"}, {"start", {0, 0}}, {"end", {0, 10}}, {"thickness", 0.25}},
           {{"id", "N"}, {"start", {0, 10}}, {"end", {4, 10}}, {"thickness", 0.25}},
           {{"id", "P"}, {"start", {9, 6}}, {"end", {12, 6}}, {"thickness", 0.1}}}}}}}};
  const common::JsonSource source{"floor.json", nullptr};
  const bim::AGraph graph = bim::buildAGraph(bim::parsePlan(common::JsonNode(plan, "", source)));
  const GraphMatcher matcher(graph);
  // B_T_M = (3, −2, 0.4): the faces in B mapped into M by its inverse.
  const Eigen::Vector3d truth(3.0, -2.0, 0.4);
  const Eigen::Rotation2Dd R(truth.z());
  const auto toM = [&](const Eigen::Vector2d& b) { return R.inverse() * (b - truth.head<2>()); };
  const auto planeOf = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, int id) {
    MatchPlane p;
    p.id = id;
    p.start = toM(a);
    p.end = toM(b);
    const Eigen::Vector2d d = (p.end - p.start).normalized();
    const Eigen::Vector2d n(-d.y(), d.x());  // left of start → end: into the floor here
    p.plane.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
    p.plane.d = -n.dot(p.start);
    return p;
  };
  MatchInput input;
  // The south façade's inner face from the corner across the 1 m gap to x = 13 (12.9 m: more
  // than S1's 5.9 m + 0.5), and the west wall's, counter-clockwise so that normals face in.
  input.planes.push_back(planeOf({0.125, 0.125}, {13.0, 0.125}, 0));
  input.planes.push_back(planeOf({0.125, 9.0}, {0.125, 0.125}, 1));
  const MatchResult result = matcher.match(input);
  EXPECT_NE(result.reason, "no S-Graph room or corner fits the plan in kind and size");
  ASSERT_GE(result.hypotheses, 1);
  const Eigen::Vector2d probe(5.0, 5.0);
  const Eigen::Vector2d at_match =
      Eigen::Rotation2Dd(result.best.x_y_yaw.z()) * probe + result.best.x_y_yaw.head<2>();
  EXPECT_LT((at_match - (R * probe + truth.head<2>())).norm(), 0.05);
  EXPECT_LT(angleError(result.best.x_y_yaw.z(), truth.z()), 0.5 * std::numbers::pi / 180.0);
}

// The acceptance bound on the unexplained wall (docs/matching.md): the truth of a clean cut is
// matched; the same S-Graph with walls the plan does not have, a third of its wall length in all,
// is "not yet", with the reason and the lengths in words.
TEST(Matching, AnAnswerLeavingMuchOfTheWallUnexplainedIsNotYet) {
  const bim::AGraph graph = referenceAGraph("d1");
  const GraphMatcher matcher(graph);
  std::mt19937_64 rng(3);
  const Eigen::Vector3d truth(-4.0, 6.0, -1.1);
  std::vector<int> all;
  for (int r = 0; r < int(graph.rooms.size()); ++r) all.push_back(r);
  auto cut = testing::cutSGraph(graph, all, truth, rng, 0.0);
  ASSERT_EQ(matcher.match(cut.input).status, MatchStatus::kMatched);
  double evidence = 0.0;
  for (const auto& p : cut.input.planes) {
    if (p.length() >= matcher.options().min_plane_length) evidence += p.length();
  }
  // 2 m walls 100 m away from the building in M: no transform near the truth explains them.
  const int walls = int(std::ceil(0.5 * evidence / 2.0));
  for (int i = 0; i < walls; ++i) {
    MatchPlane extra;
    extra.id = 1000 + i;
    extra.start = Eigen::Vector2d(100.0 + 3.0 * i, 100.0);
    extra.end = extra.start + Eigen::Vector2d(2.0, 0.0);
    extra.plane.normal = Eigen::Vector3d::UnitY();
    extra.plane.d = -100.0;
    cut.input.planes.push_back(extra);
  }
  const MatchResult result = matcher.match(cut.input);
  EXPECT_EQ(result.status, MatchStatus::kNotYet);
  EXPECT_EQ(result.reason.rfind("the plan leaves too much of the mapped wall unexplained: ", 0), 0u)
      << result.reason;
  EXPECT_NEAR(result.best.unexplained_length, 2.0 * walls, 1e-9);
  EXPECT_GT(result.best.unexplainedShare(), 0.3);
  char lengths[64];
  std::snprintf(lengths, sizeof lengths, "%.1f of %.1f m of wall explained", evidence,
                evidence + 2.0 * walls);
  EXPECT_NE(result.reason.find(lengths), std::string::npos) << result.reason;
}

// Verification by hand: the true transform explains every plane and room of a clean cut.
TEST(Matching, APlaneTurnedToTheAngleToleranceMatchesAndJustBeyondItDoesNot) {
  // The angle test's edge, through the dot-product screen in front of it: a plane turned by the
  // tolerance less a hair still explains its wall, more a hair not (either way, either sign, with
  // its normal's direction given or not).
  const bim::AGraph graph = referenceAGraph("d1");
  const GraphMatcher matcher(graph);
  const Eigen::Vector3d truth(3.0, -2.0, 0.7);
  const auto cut = everyRoomSeenFrom(graph, truth);
  std::size_t longest = 0;
  for (std::size_t i = 0; i < cut.input.planes.size(); ++i) {
    if (cut.input.planes[i].length() > cut.input.planes[longest].length()) longest = i;
  }
  const double tolerance = matcher.options().plane_angle_deg * std::numbers::pi / 180.0;
  for (const double turn : {tolerance - 1e-7, tolerance + 1e-7}) {
    for (const double sign : {1.0, -1.0}) {
      for (const bool given : {true, false}) {
        MatchInput input = cut.input;
        MatchPlane& plane = input.planes[longest];
        plane.plane.normal =
            Eigen::AngleAxisd(sign * turn, Eigen::Vector3d::UnitZ()) * plane.plane.normal;
        plane.normal_yaw = given ? std::atan2(plane.plane.normal.y(), plane.plane.normal.x())
                                 : std::numeric_limits<double>::quiet_NaN();
        const Verification v = matcher.verify(input, truth);
        const bool explained = std::any_of(v.planes.begin(), v.planes.end(),
                                           [&](const auto& m) { return m.first == plane.id; });
        EXPECT_EQ(explained, turn < tolerance) << "turned " << sign * turn << " rad";
      }
    }
  }
}

TEST(Matching, VerifyAtTheTruthExplainsEverything) {
  const bim::AGraph graph = referenceAGraph("d1");
  const GraphMatcher matcher(graph);
  const Eigen::Vector3d truth(3.0, -2.0, 0.7);
  const auto cut = everyRoomSeenFrom(graph, truth);
  const Verification v = matcher.verify(cut.input, truth);
  EXPECT_EQ(v.rooms.size(), cut.input.rooms.size());
  EXPECT_EQ(v.planes.size(), cut.input.planes.size());
  EXPECT_NEAR(v.plane_rms, 0.0, 1e-9);
  EXPECT_EQ(v.doors_missing, 0);
  // Every evidence plane's whole length is explained, none is not.
  double evidence = 0.0;
  for (const auto& p : cut.input.planes) {
    if (p.length() >= matcher.options().min_plane_length) evidence += p.length();
  }
  EXPECT_NEAR(v.explained_length, evidence, 1e-9);
  EXPECT_EQ(v.unexplained_length, 0.0);
  EXPECT_EQ(v.unexplainedShare(), 0.0);
  for (std::size_t i = 0; i < v.planes.size(); ++i) {
    const int a = v.planes[i].second;
    // The same surface, or a coplanar one facing the same way (collinear walls).
    EXPECT_NEAR(graph.surfaces[a].plane.normal.dot(
                    graph.surfaces[cut.a_surface_of_s_plane[v.planes[i].first]].plane.normal),
                1.0, 1e-9);
  }
  // Refinement from a perturbed start comes back to the truth.
  Verification off = v;
  off.x_y_yaw += Eigen::Vector3d(0.05, -0.04, 0.01);
  const Eigen::Vector3d refined = matcher.refine(cut.input, off);
  EXPECT_LT((refined - truth).norm(), 1e-6);
}

}  // namespace
}  // namespace isg::slam
