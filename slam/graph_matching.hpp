#pragma once

#include <Eigen/Geometry>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plane.hpp"

namespace isg::slam {

// Graph matching (docs/matching.md): which S-Graph rooms and wall planes are which A-Graph rooms
// and wall surfaces, and so where the map frame M lies in the plan frame B. Polynomial
// hypothesise-and-verify: every (S-room, A-room) pair of compatible kind and size proposes the
// few B_T_M its walls allow; each proposal is checked against the whole S-Graph through a grid
// index of the plan; proposals that agree are clustered, and only a unique, well-supported best
// cluster is accepted. A wrong global match is the worst failure, so anything less is "not yet"
// or "ambiguous" and the localizer simply tries again after the next map update.

// What the matcher needs of the S-Graph, in M. Built by the localizer from its graph.
struct MatchRoom {
  int id = -1;  // the S-Graph's room index
  bool four_wall = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  // The normal direction (yaw, in M) of the first plane pair and the pairs' widths; corridors
  // have one pair.
  double axis_yaw = 0.0;
  std::array<double, 2> widths{0.0, 0.0};
  std::vector<int> planes;  // ids of its wall planes
};

struct MatchPlane {
  int id = -1;       // the S-Graph's plane index
  bim::Plane plane;  // in M; normal towards the space it was seen from
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  double length() const { return (end - start).norm(); }
};

struct MatchInput {
  std::vector<MatchRoom> rooms;
  std::vector<MatchPlane> planes;
  // Pairs of indices into `rooms` the robot walked between directly (consecutive keyframes):
  // when both are matched, their A-rooms must share a doorway.
  std::vector<std::pair<int, int>> transitions;
};

struct MatchingOptions {
  double width_tolerance = 0.35;   // m, between an S-room's and an A-room's widths
  double centre_tolerance = 0.45;  // m, between room centres once transformed
  double plane_angle_deg = 8.0;
  double plane_distance = 0.15;   // m, from the S-plane's middle to the A-surface
  double plane_gap = 0.5;         // m, between the S-plane's extent and the surface's exposed parts
  double min_plane_length = 0.6;  // shorter S-planes are not used as evidence
  double room_score = 3.0;        // score of a matched room, in metres of matched wall
  // Evidence is weighted by how well it fits, exp(-½(e/σ)²): a transform 15 cm off that still
  // passes the tolerances scores far less than the right one.
  double plane_sigma = 0.05;  // m
  double room_sigma = 0.15;   // m
  // Each metre of S-plane the plan does not explain counts against a transform: shifted along a
  // row of rooms, long walls still match but the cross walls do not. Less than a matched metre
  // gains, because as built a building has walls and clutter its plan lacks.
  double unexplained_penalty = 0.5;
  double door_score = 2.0;  // a walked transition through a plan doorway (or its penalty)
  // Clustering: two hypotheses within these are the same answer.
  double cluster_distance = 0.3;
  double cluster_yaw_deg = 5.0;
  // Acceptance: ≥ min_rooms matched rooms, or one room and ≥ min_planes_outside matched planes that
  // are not its walls; and the second-best distinct answer scoring < ambiguity_ratio × the best.
  int min_rooms = 2;
  int min_planes_outside = 4;
  double ambiguity_ratio = 0.8;
  // And the best answer must explain most of the mapped wall: of the S-planes used as evidence, at
  // most this share of their length may have no A-surface. The right answer leaves unexplained
  // only what the building has and its plan lacks (extra walls, tall clutter); an answer that fits
  // one room but not the walls around it leaves whole walls. Failing it is "not yet": the map
  // grows and the share of a right answer falls (docs/matching.md).
  double max_unexplained_share = 0.25;
};

// kLost: was matched, then the world stopped agreeing with the graph; a fresh S-Graph segment is
// being matched again (docs/matching.md).
enum class MatchStatus { kNotYet, kAmbiguous, kMatched, kContradicted, kLost };
const char* toString(MatchStatus status);

// One B_T_M checked against the S-Graph: what it explains.
struct Verification {
  Eigen::Vector3d x_y_yaw = Eigen::Vector3d::Zero();  // B_T_M in the plane (z is not observed)
  double score = 0.0;
  std::vector<std::pair<int, int>> rooms;   // (S-room id, A-room index)
  std::vector<std::pair<int, int>> planes;  // (S-plane id, A-surface index)
  int doors_passed = 0;                     // transitions through a plan doorway
  int doors_missing = 0;                    // transitions between matched rooms without one
  int rooms_contradicted = 0;               // S-rooms landing on an A-room of another size
  double plane_rms = 0.0;                   // m, matched planes' distance residual
  double explained_length = 0.0;            // m of S-plane with a surface (evidence planes)
  double unexplained_length = 0.0;          // m of S-plane no surface explains
  // unexplained / (explained + unexplained); 0 with no evidence plane.
  double unexplainedShare() const;
};

struct MatchResult {
  MatchStatus status = MatchStatus::kNotYet;
  Verification best;  // the best answer (meaningful when matched or ambiguous)
  double second_score = 0.0;
  Verification second;  // the best answer distinct from `best`
  int hypotheses = 0;
  int clusters = 0;
  std::string reason;  // why not matched, or the evidence of the match, in words
  double seconds = 0.0;
  Eigen::Isometry3d B_T_M() const;  // from best.x_y_yaw, z = 0
  nlohmann::json toJson() const;
};

class GraphMatcher {
 public:
  explicit GraphMatcher(const bim::AGraph& graph, const MatchingOptions& options = {});

  // One matching attempt over the whole S-Graph.
  MatchResult match(const MatchInput& input) const;
  // Checks one B_T_M (x, y, yaw) against the S-Graph: the correspondences it implies.
  Verification verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw) const;
  // Whether two B_T_M are the same answer: they put the S-Graph's rooms (around `middle`, their
  // mean centre: middleOf) within `scale` × the clustering tolerances of each other.
  bool sameAnswer(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector2d& middle,
                  double scale = 1.0) const;
  static Eigen::Vector2d middleOf(const MatchInput& input);
  // Refines B_T_M by least squares over a verification's correspondences.
  Eigen::Vector3d refine(const MatchInput& input, const Verification& verification) const;

  const bim::AGraph& graph() const { return *graph_; }
  const MatchingOptions& options() const { return options_; }

 private:
  struct Cell {
    std::vector<int> surfaces;
    std::vector<int> rooms;
  };
  const Cell* cellAt(const Eigen::Vector2d& p) const;
  int matchRoom(const MatchRoom& room, const Eigen::Vector3d& x_y_yaw, double* distance) const;
  int matchPlane(const MatchPlane& plane, const Eigen::Vector3d& x_y_yaw, double* overlap,
                 double* distance) const;
  bool joinedByDoor(int a, int b) const;

 public:
  // Whether an S-plane, seen from B_T_M, lies within `angle_deg` and `distance` of an A-surface
  // (its normal and the distance of the S-plane's middle to the surface's plane).
  bool planeAgrees(const MatchPlane& plane, int surface, const Eigen::Vector3d& x_y_yaw,
                   double angle_deg, double distance) const;

 private:
  const bim::AGraph* graph_;
  MatchingOptions options_;
  // A uniform grid over the plan: each cell lists the surfaces passing near it and the rooms
  // whose centre (four-wall) or outline (corridor) is near it.
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 2.0;
  int columns_ = 0, rows_ = 0;
  std::vector<Cell> cells_;
  std::vector<double> surface_yaw_;  // yaw of each surface's normal
  std::vector<double> room_yaw_;     // yaw of each room's first pair normal
  std::vector<std::vector<int>> doors_of_room_;
};

}  // namespace isg::slam
