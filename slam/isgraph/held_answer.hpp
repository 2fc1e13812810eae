#pragma once

#include <Eigen/Geometry>
#include <map>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/wall_release.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// The answer the iS-Graph holds while localized: where the map frame M lies in the plan frame P,
// and which S-Graph planes and rooms are which plan surfaces and rooms. The merging optimises
// P_T_M's planar part in place (its data are a parameter block of every window); the floors give
// its height (P and B share z).
struct HeldAnswer {
  bool localized = false;
  Eigen::Vector3d P_T_M_x_y_yaw = Eigen::Vector3d::Zero();
  double P_T_M_z = 0.0;
  bool z_from_floor = false;         // P_T_M_z from a floor plane seen (not yet: as if at height 0)
  std::map<int, int> plane_matches;  // S-plane → A-surface
  std::map<int, int> room_matches;   // S-room → A-room

  // P_T_M in 3D: the planar part turned about z, and the held height.
  Eigen::Isometry3d P_T_M() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(P_T_M_x_y_yaw.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() << P_T_M_x_y_yaw.head<2>(), P_T_M_z;
    return T;
  }
  // A point of M's plane in P.
  Eigen::Vector2d inP(const Eigen::Vector2d& in_M) const {
    return applyPlanar(P_T_M_x_y_yaw, in_M);
  }
  // x_y_yaw applied to a point of the plane.
  static Eigen::Vector2d applyPlanar(const Eigen::Vector3d& x_y_yaw, const Eigen::Vector2d& p) {
    return Eigen::Rotation2Dd(x_y_yaw.z()) * p + x_y_yaw.head<2>();
  }
  // Takes a verification's correspondences (and its P_T_M): those held before are forgotten.
  void take(const Verification& answer);
  // Forgets the answer: not localized, nothing held.
  void clear();
};

// The held correspondences of the graph's current floor as the wall release judges them, in P
// under the answer's P_T_M (wall_release.hpp); with their (S-plane, A-surface) in `held` if given.
std::vector<HeldWall> heldWalls(const HeldAnswer& answer, const MatchInput& input,
                                const SGraph& graph, const bim::AGraph& plan,
                                std::vector<std::pair<int, int>>* held);

}  // namespace isg::slam
