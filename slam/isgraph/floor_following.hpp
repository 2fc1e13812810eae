#pragma once

#include <map>
#include <string>
#include <vector>

#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/held_answer.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// Which plan level each S-Graph floor is while localized (docs/matching.md, "Several storeys"),
// and the answer's height from the floor the robot stands on. A floor reached after the match is
// the level at the elevation its height above a floor of known level leads to; the robot changes
// floor only on a flight of stairs of the plan.
class FloorFollower {
 public:
  struct Options {
    // A floor's level: the plan level within this of the elevation its height leads to (m).
    double level_tolerance = 1.0;
    // On the stairs, the farthest the robot may be from every flight of its level (m).
    double flight_margin = 1.0;
  };
  // Where the robot arrived on a floor while localized: the stamp and the level it is.
  struct LevelChange {
    double stamp = 0.0;
    int floor = -1;  // the S-Graph's
    int level = -1;  // the A-Graph's
  };

  FloorFollower(const CompiledPlan& plan, const Options& options)
      : plan_(&plan), options_(options) {}

  // A new answer on plan level `level` (-1: unknown, taken as the first): the graph's current
  // floor is that level, and the answer's height is the level's elevation less the floor's
  // height seen (before the floor is seen, the most it can be: SGraph::floorBound).
  void start(int level, const SGraph& graph, HeldAnswer& answer);
  // The level of the floor the robot stands on, known or found from its height, and the answer's
  // height from it. Returns why the answer cannot hold there (a floor at no level of the plan,
  // stairs where the plan has none), empty while it can.
  std::string follow(double stamp, const SGraph& graph, HeldAnswer& answer);
  // Not localized: no floor's level is known.
  void clear() { floor_levels_.clear(); }

  int level() const { return level_; }
  // The plan level within level_tolerance of an elevation (the nearest), or -1.
  int levelAt(double elevation) const;
  // Why a pose at `p` (in P) on the stairs is on no flight of the current level's (farther than
  // flight_margin from each): the message that loses the answer; empty when it is on one.
  std::string offFlightAt(const Eigen::Vector2d& p) const;
  const std::map<int, int>& floorLevels() const { return floor_levels_; }  // S-floor → level
  const std::vector<LevelChange>& changes() const { return changes_; }

 private:
  // The plan level at the height of S-floor `floor`, from a floor whose level is known; -1 when
  // no level is within level_tolerance.
  int levelAtHeightOf(int floor, const SGraph& graph) const;

  const CompiledPlan* plan_;
  Options options_;
  std::map<int, int> floor_levels_;  // S-Graph floor → A-Graph floor, while localized
  int level_ = -1;                   // of the current floor, while localized
  std::vector<LevelChange> changes_;
};

}  // namespace isg::slam
