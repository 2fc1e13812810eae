#include "worlds/walk_crossings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "bim/as_built_wall.hpp"
#include "worlds/as_built.hpp"
#include "worlds/walk_solids.hpp"

namespace isg::worlds {

namespace {

// Taking one element can uncover another (a wall's solid closes the joint of the wall it meets):
// the walk is looked at again after each round, at most this often.
constexpr int kMaxRounds = 8;

using Interval = std::pair<double, double>;

// One pass through one planned element: the walk's points inside it, in order.
struct Pass {
  std::string element;
  bool column = false;
  std::vector<Eigen::Vector2d> points;
  int first_line = 0;
  int last_line = 0;
};

std::vector<Pass> passesThrough(const std::vector<bim::WalkPose>& walk, const WalkSolids& solids) {
  std::vector<Pass> passes;
  std::optional<Pass> open;
  forEachWalkPoint(walk, [&](const Eigen::Vector2d& p, int line) {
    const auto k = solids.solidAt(p);
    const WalkSolid* solid = k && !solids[*k].plan_id.empty() ? &solids[*k] : nullptr;
    const bool column = solid != nullptr && solid->kind == WalkSolid::Kind::kColumn;
    if (open && (solid == nullptr || solid->plan_id != open->element || column != open->column)) {
      passes.push_back(std::move(*open));
      open.reset();
    }
    if (solid == nullptr) return true;
    if (!open) open = Pass{solid->plan_id, column, {}, line, line};
    open->points.push_back(p);
    open->last_line = line;
    return true;
  });
  if (open) passes.push_back(std::move(*open));
  return passes;
}

// `built` without the gaps (each ascending), parts shorter than kMinWallPart dropped.
std::vector<Interval> withoutGaps(std::vector<Interval> built, const std::vector<Interval>& gaps) {
  for (const Interval& gap : gaps) {
    std::vector<Interval> kept;
    for (const Interval& part : built) {
      if (gap.second <= part.first || gap.first >= part.second) {
        kept.push_back(part);
        continue;
      }
      if (gap.first - part.first >= kMinWallPart) kept.push_back({part.first, gap.first});
      if (part.second - gap.second >= kMinWallPart) kept.push_back({gap.second, part.second});
    }
    built = std::move(kept);
  }
  return built;
}

// The gaps a wall's passes cut (metres along the wall as built from its start), each widened
// over the doors and windows it reaches so that no part ends inside one.
std::vector<Interval> gapsOf(const bim::Level& level, const bim::Wall& planned,
                             const bim::AsBuilt& as_built, const std::vector<const Pass*>& passes) {
  const bim::Wall built = bim::builtWall(planned, as_built);
  const Eigen::Vector2d axis = (built.end - built.start).normalized();
  std::vector<Interval> openings;
  for (const auto& door : level.doors) {
    if (door.wall == planned.id)
      openings.push_back({door.offset - 0.5 * door.width, door.offset + 0.5 * door.width});
  }
  for (const auto& window : level.windows) {
    if (window.wall == planned.id)
      openings.push_back({window.offset - 0.5 * window.width, window.offset + 0.5 * window.width});
  }
  std::vector<Interval> gaps;
  for (const Pass* pass : passes) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& p : pass->points) {
      const double t = (p - built.start).dot(axis);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    Interval gap{lo - 0.5 * kCrossingOpeningWidth, hi + 0.5 * kCrossingOpeningWidth};
    for (const Interval& opening : openings) {
      if (opening.first < gap.first && opening.second > gap.first) gap.first = opening.first;
      if (opening.first < gap.second && opening.second > gap.second) gap.second = opening.second;
    }
    gaps.push_back(gap);
  }
  return gaps;
}

void takeWallAsMissing(bim::AsBuilt& as_built, const bim::Level& level, const std::string& id) {
  as_built.missing_walls.push_back(id);
  std::erase_if(as_built.shortened_walls, [&](const auto& s) { return s.wall == id; });
  std::erase_if(as_built.wall_shifts, [&](const auto& s) { return s.wall == id; });
  std::erase_if(as_built.wall_rotations, [&](const auto& r) { return r.wall == id; });
  std::erase_if(as_built.closed_doors, [&](const std::string& door_id) {
    const bim::Door* door = level.findDoor(door_id);
    return door != nullptr && door->wall == id;
  });
}

// Opens the wall where its passes went; false when nothing of it would be left standing.
bool openWall(bim::AsBuilt& as_built, const bim::Level& level, const bim::Wall& planned,
              const std::vector<const Pass*>& passes) {
  const auto shortened =
      std::find_if(as_built.shortened_walls.begin(), as_built.shortened_walls.end(),
                   [&](const auto& s) { return s.wall == planned.id; });
  const double length = (planned.end - planned.start).norm();
  std::vector<Interval> built = shortened != as_built.shortened_walls.end()
                                    ? shortened->built
                                    : std::vector<Interval>{{0.0, length}};
  built = withoutGaps(std::move(built), gapsOf(level, planned, as_built, passes));
  if (built.empty()) return false;
  if (shortened != as_built.shortened_walls.end()) {
    shortened->built = std::move(built);
  } else {
    as_built.shortened_walls.push_back({planned.id, std::move(built)});
  }
  return true;
}

// Takes what this round's passes crossed, and keeps the passes in `crossings`.
void take(const std::vector<Pass>& passes, const bim::Level& level, bim::CrossedSolids mode,
          bim::AsBuilt& as_built, std::vector<bim::WalkCrossing>& crossings) {
  std::map<std::pair<bool, std::string>, std::vector<const Pass*>> by_element;
  for (const Pass& pass : passes) by_element[{pass.column, pass.element}].push_back(&pass);
  for (const auto& [key, element_passes] : by_element) {
    // Named, not bound: a lambda may not capture a structured binding (before C++20's clang 16).
    const bool column = key.first;
    const std::string& id = key.second;
    bool opening = false;
    if (column) {
      as_built.missing_columns.push_back(id);
      std::erase_if(as_built.moved_columns, [&](const auto& m) { return m.column == id; });
    } else if (mode == bim::CrossedSolids::kOpening &&
               openWall(as_built, level, *level.findWall(id), element_passes)) {
      opening = true;
    } else {
      takeWallAsMissing(as_built, level, id);
    }
    for (const Pass* pass : element_passes) {
      const Eigen::Vector2d at = 0.5 * (pass->points.front() + pass->points.back());
      crossings.push_back({id, column, at, pass->first_line, pass->last_line, opening});
    }
  }
}

std::string linesOf(const bim::WalkCrossing& c) {
  return c.first_line == c.last_line
             ? "line " + std::to_string(c.first_line)
             : "lines " + std::to_string(c.first_line) + "–" + std::to_string(c.last_line);
}

// One warning per element, in the order the walk first crossed them.
void sayCrossings(const bim::Scenario& scenario, common::Warnings& warnings) {
  constexpr std::size_t kNamedPasses = 3;
  const auto& crossings = scenario.robot.route.crossings;
  std::vector<std::pair<bool, std::string>> order;
  for (const auto& c : crossings) {
    if (std::find(order.begin(), order.end(), std::pair{c.column, c.element}) == order.end())
      order.push_back({c.column, c.element});
  }
  for (const auto& [column, id] : order) {
    std::string message = scenario.robot.route.trajectory_file + ": the walk crosses " +
                          (column ? "column \"" : "wall \"") + id + "\"";
    std::size_t named = 0, passes = 0;
    bool opening = false;
    for (const auto& c : crossings) {
      if (c.column != column || c.element != id) continue;
      opening = c.opening;
      if (++passes > kNamedPasses) continue;
      char at[64];
      std::snprintf(at, sizeof at, "(%.3f, %.3f)", c.at.x(), c.at.y());
      message += std::string(named++ == 0 ? " at " : ", ") + at + " (" + linesOf(c) + ")";
    }
    if (passes > kNamedPasses) {
      message += " and " + std::to_string(passes - kNamedPasses) + " more times";
    }
    message += opening ? ": taken as built with a door-wide opening where it was crossed"
                       : ": taken as not built yet on the day of the walk";
    warnings.push_back({scenario.source, "/robot/route/trajectory", message});
  }
}

}  // namespace

void forEachWalkPoint(const std::vector<bim::WalkPose>& walk,
                      const std::function<bool(const Eigen::Vector2d&, int)>& visit) {
  for (std::size_t i = 0; i < walk.size(); ++i) {
    if (i > 0) {
      const Eigen::Vector2d& a = walk[i - 1].xy;
      const Eigen::Vector2d step = walk[i].xy - a;
      const int between = int(std::ceil(step.norm() / kWalkStep)) - 1;
      for (int k = 1; k <= between; ++k) {
        if (!visit(a + step * (double(k) / double(between + 1)), walk[i].line)) return;
      }
    }
    if (!visit(walk[i].xy, walk[i].line)) return;
  }
}

void takeCrossedSolids(bim::Scenario& scenario, common::Warnings* warnings) {
  bim::Route& route = scenario.robot.route;
  if (route.kind != bim::Route::Kind::kTrajectory || route.crossed == bim::CrossedSolids::kRefuse)
    return;
  const bim::Level& plan_level = *scenario.plan.findLevel(scenario.robot.level);
  for (int round = 0; round < kMaxRounds; ++round) {
    const bim::Level built = asBuiltLevel(plan_level, scenario.as_built);
    const std::vector<Pass> passes =
        passesThrough(route.walk, WalkSolids(plan_level, built, scenario.as_built));
    if (passes.empty()) break;
    take(passes, plan_level, route.crossed, scenario.as_built, route.crossings);
  }
  std::stable_sort(route.crossings.begin(), route.crossings.end(),
                   [](const auto& a, const auto& b) { return a.first_line < b.first_line; });
  if (warnings != nullptr) sayCrossings(scenario, *warnings);
}

}  // namespace isg::worlds
