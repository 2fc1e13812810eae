#include "bim/recorded_walk.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bim/box_grid.hpp"
#include "bim/limits.hpp"
#include "common/input_error.hpp"
#include "common/tum.hpp"

namespace isg::bim {

namespace {

// The speed check looks back at least this far, so that a high-rate file's millimetre jitter
// between consecutive poses is not read as running.
constexpr double kSpeedWindow = 0.05;  // s
// At most this many gaps are named one by one; the rest are counted.
constexpr int kNamedGaps = 5;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// Whether going from a to b is faster than `max_speed`, over at least kSpeedWindow.
bool tooFast(const WalkPose& a, const WalkPose& b, double max_speed) {
  return (b.xy - a.xy).norm() > max_speed * std::max(b.t - a.t, kSpeedWindow);
}

// A single pose off the walk — too far from both its neighbours, which agree with each other (a
// tracking glitch, one frame's wrong pose) — is left out and said; the walk is bridged across it.
// Two or more in a row are a jump, refused by the speed check.
// Returns the times of the poses left out.
std::vector<double> bridgeSingleGlitches(std::vector<WalkPose>& walk, double max_speed,
                                         const std::string& path, const common::JsonNode& node) {
  std::vector<WalkPose> kept;
  std::vector<double> left_out;
  kept.reserve(walk.size());
  int glitches = 0;
  for (std::size_t i = 0; i < walk.size(); ++i) {
    const bool glitch =
        i > 0 && i + 1 < walk.size() && !kept.empty() && tooFast(kept.back(), walk[i], max_speed) &&
        tooFast(walk[i], walk[i + 1], max_speed) && !tooFast(kept.back(), walk[i + 1], max_speed);
    if (!glitch) {
      kept.push_back(walk[i]);
      continue;
    }
    left_out.push_back(walk[i].t);
    if (++glitches <= kNamedGaps) {
      const double off = (walk[i].xy - 0.5 * (kept.back().xy + walk[i + 1].xy)).norm();
      node.warn(path + ": line " + std::to_string(walk[i].line) + ": a single pose " +
                fixed(off, 3) + " m off the walk (lines " + std::to_string(kept.back().line) +
                " and " + std::to_string(walk[i + 1].line) +
                " agree): left out, the walk bridged across it");
    }
  }
  if (glitches > kNamedGaps) {
    node.warn(path + ": " + std::to_string(glitches - kNamedGaps) +
              " more single poses off the walk left out");
  }
  walk = std::move(kept);
  return left_out;
}

// Faster than anybody carries a sensor: a jump in the file (a relocalization, a wrong frame),
// which no carrier could follow and no IMU could feel sensibly. Judged over kSpeedWindow or more,
// so that a high-rate file's millimetre jitter between consecutive poses is not read as running.
void checkCarriedSpeed(const std::vector<WalkPose>& walk, const std::string& path) {
  std::size_t back = 0;
  for (std::size_t i = 1; i < walk.size(); ++i) {
    while (back + 1 < i && walk[i].t - walk[back + 1].t >= kSpeedWindow) ++back;
    const std::size_t from = walk[i].t - walk[back].t >= kSpeedWindow ? back : i - 1;
    const double distance = (walk[i].xy - walk[from].xy).norm();
    const double speed = distance / (walk[i].t - walk[from].t);
    if (speed <= kMaxCarriedSpeed) continue;
    throw common::InputError(
        path, "",
        "line " + std::to_string(walk[i].line) + ": the walk moves " + fixed(distance, 3) +
            " m in " + fixed(walk[i].t - walk[from].t, 3) + " s since line " +
            std::to_string(walk[from].line) + " (" + fixed(speed, 1) +
            " m/s; nobody carries a sensor faster than " + fixed(kMaxCarriedSpeed, 0) +
            " m/s: a jump, or a pose in another frame?)");
  }
}

}  // namespace

LoadedWalk readRecordedWalk(const std::string& path, const Level& level,
                            const common::JsonNode& node) {
  LoadedWalk loaded;
  // Every pose of a walk is held while the run goes (its route, its ground truth): the file is
  // held to a size whose poses fit in memory before any of it is read.
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > kMaxWalkFileBytes) {
    throw common::InputError(path, "",
                             "the walk's file is " + std::to_string(bytes) + " bytes; at most " +
                                 std::to_string(kMaxWalkFileBytes) +
                                 " are read (docs/simulation.md, \"Replayed walks\"): thin it out "
                                 "(a pose every 0.01 s is plenty) or cut it");
  }
  std::vector<int> lines;
  common::Trajectory poses;
  try {
    poses = common::readTum(path, &lines);
  } catch (const common::TumError& e) {
    throw common::InputError(path, "", e.located());
  }
  if (poses.size() < 2) {
    throw common::InputError(path, "",
                             poses.empty() ? "no poses (a TUM file holds one pose per line)"
                                           : "one pose only: a walk needs two or more");
  }
  const auto at = [&](std::size_t i) { return "line " + std::to_string(lines[i]) + ": "; };
  const double t0 = poses.front().t;
  loaded.recording_start = t0;
  const double length = poses.back().t - t0;
  if (length > limits::kMaxRobotSeconds) {
    throw common::InputError(path, "",
                             at(poses.size() - 1) + "the walk lasts " + fixed(length, 0) +
                                 " s; at most " + fixed(limits::kMaxRobotSeconds, 0) +
                                 " s of robot time are simulated");
  }
  std::vector<WalkPose> walk;
  walk.reserve(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto& R = poses[i].pose.linear();
    // Rz(yaw)·Ry(pitch)·Rx(roll), pitch within ±90°.
    walk.push_back({poses[i].t - t0, poses[i].pose.translation().head<2>(),
                    std::atan2(R(1, 0), R(0, 0)), lines[i], poses[i].pose.translation().z(),
                    std::atan2(R(2, 1), R(2, 2)), std::asin(std::clamp(-R(2, 0), -1.0, 1.0))});
  }

  loaded.bridged = bridgeSingleGlitches(walk, kMaxCarriedSpeed, path, node);
  checkCarriedSpeed(walk, path);

  int gaps = 0;
  for (std::size_t i = 1; i < walk.size(); ++i) {
    const double gap = walk[i].t - walk[i - 1].t;
    if (gap <= kWalkGapWarning) continue;
    if (++gaps <= kNamedGaps) {
      node.warn(path + ": lines " + std::to_string(walk[i - 1].line) + "–" +
                std::to_string(walk[i].line) + ": " + fixed(gap, 2) +
                " s without a pose; the walk is interpolated across the gap");
    }
  }
  if (gaps > kNamedGaps) {
    node.warn(path + ": " + std::to_string(gaps - kNamedGaps) + " more gaps of over " +
              fixed(kWalkGapWarning, 0) + " s without a pose");
  }

  std::vector<Eigen::Vector2d> corners;
  for (const auto& w : level.walls) {
    corners.push_back(w.start);
    corners.push_back(w.end);
  }
  if (!corners.empty()) {
    const Box2 near = Box2::around(corners).grown(kWalkOutsideWarning);
    for (const auto& pose : walk) {
      if (near.contains(pose.xy)) continue;
      node.warn(path + ": line " + std::to_string(pose.line) + ": the walk is at (" +
                fixed(pose.xy.x(), 2) + ", " + fixed(pose.xy.y(), 2) + "), over " +
                fixed(kWalkOutsideWarning, 0) + " m beyond level \"" + level.id +
                "\"'s walls: are its positions in the plan frame?");
      break;
    }
  }
  loaded.walk = std::move(walk);
  return loaded;
}

}  // namespace isg::bim
