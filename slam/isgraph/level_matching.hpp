#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/isgraph/graph_matching.hpp"

namespace isg::slam {

// Matching across the levels of a building (docs/matching.md, "Several storeys"). The S-Graph's
// current floor is matched against each level's A-Graph on its own: a level is a plan of its
// own, and walls of two storeys stand in the same place. The answers of the levels then compete
// as the answers of one level do: the best must lead every other level's best decisively on the
// evidence where they disagree, or the result is ambiguous. Floors that look alike are a symmetry
// of the building, never a guess.

// One level of an A-Graph as a graph of its own, and the way back to the whole graph's indices.
struct LevelGraph {
  int floor = -1;  // index into the whole AGraph::floors
  bim::AGraph graph;
  std::vector<int>
      surface_in_whole;  // this graph's surface i is the whole graph's surface_in_whole[i]
  std::vector<int> room_in_whole;
};
LevelGraph levelGraph(const bim::AGraph& whole, int floor);

struct LevelMatch {
  MatchResult result;  // its indices into the whole A-Graph
  int level = -1;      // the floor of the A-Graph its best answer is on (-1: none)
  // Other levels whose best answer the best does not lead decisively: the floors alike.
  std::vector<int> alike_levels;
};

class LevelMatcher {
 public:
  LevelMatcher(const bim::AGraph& whole, const MatchingOptions& options);
  LevelMatcher(const LevelMatcher&) = delete;
  LevelMatcher& operator=(const LevelMatcher&) = delete;

  int levels() const { return int(levels_.size()); }
  // One matching attempt against every level.
  LevelMatch match(const MatchInput& input, ThreadPool* pool = nullptr) const;
  // verify() on one level, its indices into the whole A-Graph.
  Verification verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw, int level) const;
  const GraphMatcher& matcher(int level) const { return *levels_[level].matcher; }

 private:
  struct Level {
    LevelGraph graph;
    std::unique_ptr<GraphMatcher> matcher;  // points into graph.graph
  };
  Verification inWhole(const Verification& v, int level) const;
  const bim::AGraph* whole_;
  std::deque<Level> levels_;  // one per A-Graph floor
};

}  // namespace isg::slam
