#include "cli/route_check.hpp"

#include <algorithm>
#include <cstdio>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/plural.hpp"

namespace isg::cli {

namespace {

// A replayed walk's path further than this from one of its file's poses is said.
constexpr double kWalkDeviationWarning = 0.05;  // m

}  // namespace

double checkRoute(const std::string& command, const bim::Scenario& scenario,
                  const sim::Simulation& simulation, double duration) {
  const auto& route = simulation.route();
  // One line however many: the first ten by name and the count.
  if (route.skipped_rooms.size() == 1) {
    std::fprintf(stderr, "%s: warning: room %s cannot be reached; the tour skips it\n",
                 command.c_str(), route.skipped_rooms.front().c_str());
  } else if (!route.skipped_rooms.empty()) {
    std::fprintf(stderr, "%s: warning: rooms %s cannot be reached; the tour skips them\n",
                 command.c_str(), common::namedList(route.skipped_rooms).c_str());
  }
  for (const auto& level : route.skipped_levels) {
    const auto why = route.why_levels_skipped.find(level);
    std::fprintf(
        stderr, "%s: warning: level %s cannot be reached (%s); the tour skips it\n",
        command.c_str(), level.c_str(),
        why == route.why_levels_skipped.end() ? "no flight leads there" : why->second.c_str());
  }
  if (const sim::WalkPath* walk = simulation.baseMotion().walk();
      walk != nullptr && walk->maxDeviation() > kWalkDeviationWarning) {
    std::fprintf(stderr,
                 "%s: warning: %s: the replayed path passes %.3f m from the file's pose at line "
                 "%d (median %.3f m): the walk is smoothed over %.1f s (docs/simulation.md)\n",
                 command.c_str(), scenario.robot.route.trajectory_file.c_str(),
                 walk->maxDeviation(), walk->maxDeviationLine(), walk->medianDeviation(),
                 sim::kWalkKnotSpacing);
  }
  const double route_seconds = simulation.duration();
  const double seconds = duration < 0 ? route_seconds : std::min(duration, route_seconds);
  if (simulation.scanCount(seconds) == 0) {
    const std::string why =
        route_seconds <= 0.0
            ? "the robot has nowhere to go: the route from its start reaches no other room or "
              "point (a one-room plan, or every door closed)"
            : "the route takes " + common::formatNumber(route_seconds) +
                  " s, shorter than one LiDAR turn";
    throw common::InputError(
        scenario.source, "/robot/route",
        "no scan would be recorded: " + why + "; give robot.route.waypoints (docs/formats.md)");
  }
  if (duration > route_seconds + 1e-9) {
    std::fprintf(stderr,
                 "%s: warning: --duration %s s is longer than the route (%s s); the run ends "
                 "with the route\n",
                 command.c_str(), common::formatNumber(duration).c_str(),
                 common::formatNumber(route_seconds).c_str());
  }
  return seconds;
}

}  // namespace isg::cli
