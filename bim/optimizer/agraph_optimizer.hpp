#pragma once

#include <ceres/ceres.h>
#include <numbers>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/optimizer/plane_manifold.hpp"

namespace isg::bim {

// Standard deviations of the A-Graph's factors. The plan is exact up to how it was drawn, so
// the defaults are a centimetre and half a degree.
struct AGraphSigmas {
  double plane_angle = 0.5 * std::numbers::pi / 180.0;  // rad, plane priors
  double plane_distance = 0.01;                         // m, plane priors
  double wall = 0.01;                                   // m, wall centres
  double room = 0.01;                                   // m, room centres
  double doorway = 0.02;                                // m, doorways
};

// The A-Graph's nodes as Ceres parameter blocks, initialised from the graph, and the factors
// between them. The state owns the blocks; the problem only points at them, so the state must
// outlive it. The iS-Graph adds these blocks and factors to its own problem.
class AGraphState {
 public:
  explicit AGraphState(const AGraph& graph);

  // Adds every parameter block (planes on the PlaneManifold, doorway z held constant) and every
  // factor: walls, four- and two-wall rooms, doorways; with `plane_priors`, also one prior per
  // surface at the plan's value, which pins the graph to the plan frame.
  void addToProblem(ceres::Problem& problem, const AGraphSigmas& sigmas, bool plane_priors);

  // Runs Ceres on a problem with just this graph; returns the final cost.
  double optimize(const AGraphSigmas& sigmas = {}, bool plane_priors = true,
                  bool fix_planes = false);

  std::vector<Eigen::Vector4d> planes;    // [n, d] per surface
  std::vector<Eigen::Vector3d> walls;     // ω per wall
  std::vector<Eigen::Vector2d> rooms;     // ρ per room
  std::vector<Eigen::Vector3d> doorways;  // D per doorway

  const AGraph& graph() const { return *graph_; }

 private:
  const AGraph* graph_;
  std::unique_ptr<PlaneManifold> plane_manifold_;
  std::unique_ptr<ceres::SubsetManifold> doorway_manifold_;
};

}  // namespace isg::bim
