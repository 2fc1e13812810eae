#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "slam/match_status.hpp"
#include "slam/sight_profile.hpp"

namespace isg::slam {

// What a localizer that builds a map can tell about it, as plain data: the keyframe estimates
// (with the odometry at the same instants, to compare), the wall planes and confirmed rooms, and
// the time each keyframe cost. `isg slam` reports these; nothing outside slam needs the S-Graph.
struct KeyframeTiming {
  double extraction_s = 0.0;    // the front end: deskew, registration, planes, association
  double planes_s = 0.0;        // of which plane extraction alone
  double solve_s = 0.0;         // of optimisation_s: the window's solve and plane merging
  double optimisation_s = 0.0;  // the window optimisation, plane merging and room detection
  // The window problem's size: what its solve time follows. Bounded by the window and the
  // anchors per plane, whatever the length of the run.
  int window_residuals = 0;
  int window_parameters = 0;
};

struct MapKeyframe {
  double stamp = 0.0;
  Eigen::Isometry3d estimate = Eigen::Isometry3d::Identity();  // M_T_R, optimised
  Eigen::Isometry3d odometry = Eigen::Isometry3d::Identity();  // M_T_R by odometry alone
  // How far it saw around (empty on the stairs, and from localizers that do not record it).
  SightProfile sight;
  // Which of the map's segments it belongs to, 0 the first (MapDiagnostics::current_segment).
  int segment = 0;
};

struct MapRoom {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // in M
  bool four_wall = true;                             // else a corridor: widths[0] only
  std::array<double, 2> widths{0.0, 0.0};            // metres
};

// A wall plane of the map, as the map holds it at the end: oriented toward where it was seen
// from, with its extent along the wall and the heights it was seen at. Only planes seen as walls
// (not clutter) and not merged into another.
struct MapWall {
  int id = -1;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // in M
  double d = 0.0;                                     // n·x + d = 0 on the plane
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();  // in M
  double z_min = 0.0, z_max = 0.0;                                                 // in M
  int observations = 0;
  std::vector<int> keyframes;  // that observed it: indices into MapDiagnostics::keyframes
  // Where along it, in metres from `start`, enough of its observations saw it (the S-Graph's:
  // at least two of them); empty when the map does not say (then start…end).
  std::vector<std::pair<double, double>> confirmed;
};

struct MapDiagnostics {
  std::vector<MapKeyframe> keyframes;
  // keyframes[current_segment..] are the current segment's, in M with its walls. Those before it
  // are of segments that ended (the map was restarted where the scans disagreed with it): each
  // segment only continues M from the pose it ended at, so they may lie decimetres off the
  // current segment's keyframes of the same places.
  std::size_t current_segment = 0;
  std::size_t planes = 0;
  std::vector<MapWall> walls;
  std::vector<MapRoom> rooms;  // confirmed rooms
  std::vector<KeyframeTiming> timings;
};

// One change of a global localizer's status (e.g. the matcher's "not yet" → "matched"), for the
// run's log and metrics.json's `matching_events`.
struct StatusChange {
  double stamp = 0.0;
  int keyframe = 0;
  MatchStatus status = MatchStatus::kNotYet;
  std::string reason;
};

}  // namespace isg::slam
