// PathSearch: one search state kept over many searches on a grid gives the paths that a fresh
// search gives each time, whatever the searches before it left behind.
#include "sim/path_search.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <queue>
#include <random>

#include "sim/four_ary_heap.hpp"
#include "sim/route_planner.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

TEST(PathSearch, ReusedOverManySearchesGivesTheFreshSearchsPaths) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d6", nullptr);
  const bim::Level& level = scenario.plan.levels.at(0);
  const OccupancyGrid grid(scenario.plan, scenario.as_built, level.id);
  std::vector<Eigen::Vector2d> goals;
  for (const auto& room : level.rooms) goals.push_back(roomGoal(grid, room));
  ASSERT_GE(goals.size(), 6u);
  PathSearch search(grid);
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, goals.size() - 1);
  int found = 0;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector2d& from = goals[pick(rng)];
    const Eigen::Vector2d& to = goals[pick(rng)];
    const std::vector<Eigen::Vector2d> reused = search.find(from, to, kMinClearance);
    const std::vector<Eigen::Vector2d> fresh = PathSearch(grid).find(from, to, kMinClearance);
    ASSERT_EQ(reused.size(), fresh.size()) << i;
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      ASSERT_EQ(reused[k], fresh[k]) << i << " " << k;  // bit for bit
    }
    if (!fresh.empty()) ++found;
    // A search that cannot start (no cell of D6 is 5 m from every wall) returns nothing, and the
    // next reused search must still match its fresh one.
    EXPECT_TRUE(search.find(from, to, 5.0).empty());
  }
  EXPECT_EQ(found, 40);  // every room of D6 is reachable from every other
}

// Endpoints as given, cell centres between them, each a step to a neighbouring cell (8-connected)
// that keeps the clearance.
TEST(PathSearch, APathRunsFromItsStartToItsGoalThroughNeighbouringCells) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1", nullptr);
  const bim::Level& level = scenario.plan.levels.at(0);
  const OccupancyGrid grid(scenario.plan, scenario.as_built, level.id);
  const Eigen::Vector2d from = roomGoal(grid, level.rooms.front());
  const Eigen::Vector2d to = roomGoal(grid, level.rooms.back());
  PathSearch search(grid);
  const auto path = search.find(from, to, kMinClearance);
  ASSERT_GE(path.size(), 3u);
  EXPECT_EQ(path.front(), from);
  EXPECT_EQ(path.back(), to);
  for (std::size_t k = 1; k + 1 < path.size(); ++k) {
    const Eigen::Vector2i cell = grid.cellOf(path[k]);
    EXPECT_GE(grid.clearance(cell), kMinClearance) << k;
    if (k + 2 < path.size()) {
      const Eigen::Vector2i step = grid.cellOf(path[k + 1]) - cell;
      EXPECT_EQ(step.cwiseAbs().maxCoeff(), 1) << k;
    }
  }
}

// The search's open set pops distinct (f, cell) pairs in the order std::priority_queue did, pushes
// and pops interleaved as A* interleaves them, ties in f broken by the cell.
TEST(FourAryHeap, PopsInTheStandardPriorityQueuesOrder) {
  FourAryHeap heap;
  std::priority_queue<FourAryHeap::Entry, std::vector<FourAryHeap::Entry>, std::greater<>> queue;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> key(0, 50);  // few keys: many ties in f
  std::uniform_int_distribution<int> action(0, 2);
  int next_value = 0, popped = 0;
  for (int step = 0; step < 20000; ++step) {
    if (action(rng) > 0 || queue.empty()) {
      const FourAryHeap::Entry entry{0.25 * key(rng), (next_value++ * 7919) % 100003};
      heap.push(entry);
      queue.push(entry);
    } else {
      ASSERT_EQ(heap.top(), queue.top()) << step;
      heap.pop();
      queue.pop();
      ++popped;
    }
    ASSERT_EQ(heap.size(), queue.size());
  }
  for (; !queue.empty(); queue.pop(), heap.pop(), ++popped) ASSERT_EQ(heap.top(), queue.top());
  EXPECT_TRUE(heap.empty());
  EXPECT_GT(popped, 10000);
}

}  // namespace
}  // namespace isg::sim
