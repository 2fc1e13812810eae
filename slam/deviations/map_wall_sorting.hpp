#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/deviation_options.hpp"

namespace isg::slam {

// A map wall carried into B.
struct WallInB {
  int plane = -1;
  Eigen::Vector2d normal, start, end;
  double z_min = 0.0, z_max = 0.0;
  int observations = 0;
  double lean_deg = 0.0;      // of its plane off vertical
  bool behind_walls = false;  // seen only through other map walls (seenOnlyThroughWalls)
  // MapWall::confirmed as shares of start → end (a placement keeps them); empty: all of it.
  std::vector<std::pair<double, double>> confirmed;
  double length() const { return (end - start).norm(); }
  Eigen::Vector2d middle() const { return 0.5 * (start + end); }
};

// What a map wall standing on a level is to the report (docs/deviations.md, "Extra walls"): the
// stages a map wall passes, in order, the first that takes it deciding.
enum class MapWallRole {
  // Evidence for the one plan surface it lies along (surfaceOf).
  kEvidence,
  // Along several plan faces in line, or along one face only in part (a façade of bays between
  // columns seen as one plane): evidence for each, by the piece along it (piecesAlongFaces).
  kAlongFacesInLine,
  // All along a rectangular column: a face of it, judged with the columns (onColumn).
  kOnColumn,
  // Seen from fewer than min_deviation_observations keyframes and leaning more than
  // max_stray_lean_deg off vertical, or seen only through other map walls: a stray fit (isStray).
  kStray,
  // None of those: a wall the plan lacks (paired into extra walls).
  kUnexplained,
};

struct SortedMapWall {
  MapWallRole role = MapWallRole::kUnexplained;
  int surface = -1;                             // kEvidence: index into AGraph::surfaces
  std::vector<std::pair<int, WallInB>> pieces;  // kAlongFacesInLine: (surface, piece along it)
};

// The map wall `m` of `level` through the stages above.
SortedMapWall sortMapWall(const bim::AGraph& plan, const std::string& level, const WallInB& m,
                          const DeviationOptions& options);

// The stages, each on its own (DeviationOptions names their thresholds).
int surfaceOf(const bim::AGraph& plan, const std::string& level, const WallInB& m,
              const DeviationOptions& options);
std::vector<std::pair<int, WallInB>> piecesAlongFaces(const bim::AGraph& plan,
                                                      const std::string& level, const WallInB& m,
                                                      const DeviationOptions& options);
bool onColumn(const bim::AGraph& plan, const std::string& level, const WallInB& m,
              const DeviationOptions& options);
bool isStray(const WallInB& m, const DeviationOptions& options);

}  // namespace isg::slam
