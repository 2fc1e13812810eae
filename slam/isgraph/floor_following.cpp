#include "slam/isgraph/floor_following.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace isg::slam {

void FloorFollower::start(int level, const SGraph& graph, HeldAnswer& answer) {
  const auto& floors = plan_->agraph().floors;
  // z: walls do not observe it; the floor does.
  const double elevation = level >= 0       ? floors[level].elevation
                           : floors.empty() ? 0.0
                                            : floors[0].elevation;
  // Before the floor is seen, the most it can be (SGraph::floorBound).
  answer.P_T_M_z = elevation - graph.floorHeight().value_or(graph.floorBound().value_or(0.0));
  answer.z_from_floor = graph.floorHeight().has_value();
  level_ = level >= 0 ? level : 0;
  floor_levels_.clear();
  if (graph.currentFloor() >= 0) floor_levels_[graph.currentFloor()] = level_;
}

int FloorFollower::levelAt(double elevation) const {
  const auto& levels = plan_->agraph().floors;
  int best = -1;
  for (int l = 0; l < int(levels.size()); ++l) {
    const double off = std::abs(levels[l].elevation - elevation);
    if (off <= options_.level_tolerance &&
        (best < 0 || off < std::abs(levels[best].elevation - elevation))) {
      best = l;
    }
  }
  return best;
}

int FloorFollower::levelAtHeightOf(int floor, const SGraph& graph) const {
  const auto& floors = graph.floors();
  if (floor_levels_.empty() || floor < 0 || floor >= int(floors.size())) return -1;
  // From the lowest-numbered floor whose level is known; any would do: M is one frame, and the
  // heights of its floors differ by the storeys climbed.
  const auto& [known_floor, known_level] = *floor_levels_.begin();
  return levelAt(plan_->agraph().floors[known_level].elevation + floors[floor].robot_z -
                 floors[known_floor].robot_z);
}

std::string FloorFollower::offFlightAt(const Eigen::Vector2d& p) const {
  const auto& level = plan_->agraph().floors[level_];
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& flight : plan_->flights()) {
    if (flight.joins(level.elevation, options_.level_tolerance)) {
      nearest = std::min(nearest, flight.distance(p));
    }
  }
  if (nearest <= options_.flight_margin) return "";
  const Eigen::Vector2d in_B = p + plan_->B_t_P();
  char text[200];
  if (std::isinf(nearest)) {
    std::snprintf(text, sizeof text,
                  "the robot is on stairs at (%.1f, %.1f), and no flight of the plan joins level "
                  "%s",
                  in_B.x(), in_B.y(), level.id.c_str());
  } else {
    std::snprintf(text, sizeof text,
                  "the robot is on stairs at (%.1f, %.1f), %.1f m from every flight that joins "
                  "level %s",
                  in_B.x(), in_B.y(), nearest, level.id.c_str());
  }
  return text;
}

std::string FloorFollower::follow(double stamp, const SGraph& graph, HeldAnswer& answer) {
  const auto& levels = plan_->agraph().floors;
  const int floor = graph.currentFloor();
  if (!plan_->severalLevels()) {
    // The floor's height as it is known now (its observations accumulate), or before it was
    // seen, the most it can be.
    if (graph.floorHeight()) {
      answer.P_T_M_z = levels[level_].elevation - *graph.floorHeight();
      answer.z_from_floor = true;
    } else if (!answer.z_from_floor && graph.floorBound()) {
      answer.P_T_M_z = levels[level_].elevation - *graph.floorBound();
    }
    return "";
  }
  if (floor < 0) return "";
  // Between floors (the current floor is the last one stood on).
  if (graph.keyframes().back().floor < 0) {
    return offFlightAt(answer.inP(graph.keyframes().back().pose().translation().head<2>()));
  }
  const auto known = floor_levels_.find(floor);
  if (known != floor_levels_.end()) {
    level_ = known->second;
  } else {
    const int level = levelAtHeightOf(floor, graph);
    if (level < 0) {
      char text[160];
      std::snprintf(
          text, sizeof text,
          "the robot reached a floor %.1f m from where it was matched, and no level of "
          "the plan is there",
          graph.floors()[floor].robot_z - graph.floors()[floor_levels_.begin()->first].robot_z);
      return text;
    }
    floor_levels_[floor] = level;
    level_ = level;
    changes_.push_back({stamp, floor, level});
  }
  if (const auto height = graph.floorHeight(floor)) {
    answer.P_T_M_z = levels[level_].elevation - *height;
    answer.z_from_floor = true;
  }
  return "";
}

}  // namespace isg::slam
