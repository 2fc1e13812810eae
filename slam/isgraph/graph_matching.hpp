#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plane.hpp"
#include "common/angles.hpp"
#include "slam/match_status.hpp"
#include "slam/thread_pool.hpp"

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
  // The normal's direction in the plane (atan2), when its maker computed it once (matchInputOf):
  // every hypothesis of a match asks for it, thousands of times a plane on a large building.
  // NaN: not given; normalYaw() computes it.
  double normal_yaw = std::numeric_limits<double>::quiet_NaN();
  double length() const { return (end - start).norm(); }
  double normalYaw() const {
    return std::isnan(normal_yaw) ? std::atan2(plane.normal.y(), plane.normal.x()) : normal_yaw;
  }
};

// A transform (x, y, yaw) in the plane with its rotation computed once: a hypothesis places every
// S-plane and S-room with it (a sine and cosine per hypothesis, not per plane). Made implicitly
// from (x, y, yaw).
struct Placement {
  Placement(const Eigen::Vector3d& transform)  // NOLINT(google-explicit-constructor)
      : x_y_yaw(transform), R(Eigen::Rotation2Dd(transform.z()).toRotationMatrix()) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return R * p + x_y_yaw.head<2>(); }
  double yaw() const { return x_y_yaw.z(); }
  Eigen::Vector3d x_y_yaw;
  Eigen::Matrix2d R;
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
  // Acceptance (docs/matching.md), first on the best answer alone: ≥ min_rooms matched rooms, or
  // one room and ≥ min_planes_outside matched planes that are not its walls, or, with no room,
  // ≥ min_planes_without_rooms matched planes facing two directions at least 30° apart.
  int min_rooms = 2;
  int min_planes_outside = 4;
  int min_planes_without_rooms = 8;
  // And it must explain most of the S-Graph on its own: of the S-planes used as evidence, at most
  // this share of their length may have no A-surface, and at least min_room_share of the S-rooms
  // must have an A-room. The right answer leaves unexplained only what the building has and its
  // plan lacks (extra walls, tall clutter, a missing wall joining two rooms); an answer that fits
  // one room but not the walls around it leaves whole walls. Failing it is "not yet".
  double max_unexplained_share = 0.25;
  // An S-plane no surface explains within the tolerances above, but that lies within these of a
  // plan surface facing the same way (its segment coming that close to the surface's line, the
  // extent reaching it as above), is read as that wall built off the plan: the localizer is
  // meant to hold walls shifted up to 35 cm and turned up to 15° (docs/matching.md). It earns
  // nothing and costs the unexplained penalty in the score, as before, but adequacy does not
  // count it as unexplained.
  double deviation_distance = 0.4;  // m
  double deviation_angle_deg = 15.0;
  // Each finalist is also tried moved to where the most walls facing each way agree
  // (slam/isgraph/match_consensus.cpp): up to this many of the strongest shifts per direction,
  // the two most walled directions combined. Walls, not metres, vote: a wall is built off the
  // plan or not whatever its length, so one long wall built off must not outvote several short
  // ones built as planned. A move is taken when it puts at least consensus_min_walls more plan
  // walls on their surfaces (each counted by its best fit, exp(−½(e/plane_sigma)²)).
  int consensus_modes = 3;
  double consensus_min_walls = 2.0;
  double min_room_share = 0.5;
  // Then against every other answer among the finalists, on what distinguishes them: the score
  // is a sum over the S-Graph's walls, rooms and walked doorways, so what both answers explain
  // alike cancels, and the difference is the evidence on which they disagree. The best must lead
  // every other answer by at least min_decisive_evidence (in the score's metres of wall); else
  // "ambiguous". Not a ratio: the more of a symmetric building the robot has seen, the larger
  // both totals, however decisive the part where the answers differ.
  double min_decisive_evidence = 4.0;  // m
  // And by at least decisive_sigmas × √(disagreement), the disagreement being the sum of the
  // absolute differences (in the same metres) over every element: read each metre of evidence
  // as noise of unit variance, a lead that the noise of the disagreeing part could make is not
  // decisive. Two answers that each explain walls the other does not (an early, bent map, or a
  // near-repeat shifted by a room) must differ by more than two that disagree only on one room.
  double decisive_sigmas = 2.0;
  int finalists = 6;  // distinct answers refined and compared
  // Seeds beyond four-wall rooms (docs/matching.md): corridors slide along their axis until a
  // wall across them lines up; corners of two long walls (constellations) seed too, at every
  // attempt. Corner arms shorter than min_corner_arm are not used, and only the max_corners
  // corners with the longest arms.
  double min_corner_arm = 1.5;  // m
  int max_corners = 6;
  // A long corridor proposes thousands of slides (every S-wall across it on every A-surface that
  // faces its way: 2.5–4.5 k a corridor pair on a 195-office floor), each verified against the
  // whole map. A pair keeps at most this many: those that the most S-wall length proposes, within
  // cluster_distance of the slide — the right slide is proposed by every wall across the corridor
  // that lies on its surface, a coincidence by few.
  int max_corridor_slides = 512;
  double corner_gap = 0.6;  // m, between two walls' ends to make a corner
  // Two walls make a corner when their normals are at least this far apart (and at most 180° less
  // it): a non-Manhattan plan's walls meet at 50° or 65° as well as 90°. Below it the crossing of
  // their lines is too ill-conditioned to place a seed (1 cm across the walls moves it 2 cm along
  // them at 30°).
  double min_corner_angle_deg = 30.0;
  // The sine of min_corner_angle_deg: the least |n₁ × n₂| of two walls that make a corner.
  double minCornerSine() const { return std::sin(common::radians(min_corner_angle_deg)); }
};

// One B_T_M checked against the S-Graph: what it explains.
struct Verification {
  Eigen::Vector3d x_y_yaw = Eigen::Vector3d::Zero();  // B_T_M in the plane (z is not observed)
  double score = 0.0;
  std::vector<std::pair<int, int>> rooms;   // (S-room id, A-room index)
  std::vector<std::pair<int, int>> planes;  // (S-plane id, A-surface index)
  int doors_passed = 0;                     // transitions through a plan doorway
  int doors_missing = 0;                    // transitions between matched rooms without one
  int rooms_contradicted = 0;               // S-rooms landing on an A-room of another size
  std::vector<int> contradicted;            // their ids
  // Per input transition: +1 through a plan doorway, -1 between matched rooms without one, 0 not
  // both matched.
  std::vector<int> transition_doors;
  double plane_rms = 0.0;           // m, matched planes' distance residual
  double explained_length = 0.0;    // m of S-plane with a surface (evidence planes)
  double unexplained_length = 0.0;  // m of S-plane no surface explains
  // Of unexplained_length, the m of S-plane near a surface as a wall built off it would be.
  double built_off_length = 0.0;
  // What adequacy counts: (unexplained − built off) / (explained + unexplained); 0 with no
  // evidence plane.
  double unexplainedShare() const;
};

// What separates the best answer from another one: the evidence on which they disagree.
struct Distinction {
  // Walls (m of score) and rooms, doorways (counts) whose score favours the best / the other;
  // an element counts when its scores differ by ≥ 5 % of its wall's length or half a room's.
  double walls_for = 0.0, walls_against = 0.0;
  int rooms_for = 0, rooms_against = 0;
  int doors_for = 0, doors_against = 0;
  double evidence = 0.0;      // in metres of wall, for the best
  double disagreement = 0.0;  // Σ |difference| over every element, metres
  // Where to look: A-rooms (ids) the other answer's turn of the plan maps onto nothing alike, so
  // that seeing them would separate the two; empty when the plan is symmetric under it.
  std::vector<std::string> separating_rooms;
  std::string describe() const;
};

struct Candidate {
  Verification answer;
  Distinction from_best;
};

struct MatchResult {
  MatchStatus status = MatchStatus::kNotYet;
  Verification best;  // the best answer (meaningful when matched or ambiguous)
  double second_score = 0.0;
  Verification second;  // the other answer the best leads least (by decisive evidence)
  // The other finalists, each with what separates it from the best, least separated first.
  std::vector<Candidate> candidates;
  int hypotheses = 0;
  int clusters = 0;
  std::string reason;  // why not matched, or the evidence of the match, in words
  double seconds = 0.0;
  Eigen::Isometry3d B_T_M() const;  // from best.x_y_yaw, z = 0
  // The same result with every answer's x, y moved by `shift` (into another frame that differs
  // from the matcher's by a translation).
  MatchResult translated(const Eigen::Vector2d& shift) const;
  nlohmann::json toJson() const;
  // The best answer and the other candidates, each with its B_T_M, score and what separates it
  // from the best (the evidence on which they disagree, the plan rooms that would tell them apart).
  nlohmann::json candidatesJson() const;
};

class GraphMatcher {
 public:
  explicit GraphMatcher(const bim::AGraph& graph, const MatchingOptions& options = {});

  // One matching attempt over the whole S-Graph.
  // `pool`, when given, verifies the hypotheses on its threads too (each verification stands on
  // its own: the result is the same with any number of threads).
  MatchResult match(const MatchInput& input, ThreadPool* pool = nullptr) const;
  // Checks one B_T_M (x, y, yaw) against the S-Graph: the correspondences it implies.
  Verification verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw) const;
  // Whether two B_T_M are the same answer: they put the S-Graph's rooms (around `middle`, their
  // mean centre: middleOf) within `scale` × the clustering tolerances of each other.
  bool sameAnswer(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector2d& middle,
                  double scale = 1.0) const;
  static Eigen::Vector2d middleOf(const MatchInput& input);
  // What separates `best` from `other`, both verified on `input` (see MatchingOptions); `other`
  // scored by `other_matcher` when given (an answer on another level of the building,
  // slam/isgraph/level_matching.hpp), by this matcher otherwise.
  Distinction distinguish(const MatchInput& input, const Verification& best,
                          const Verification& other,
                          const GraphMatcher* other_matcher = nullptr) const;
  // Whether a distinction is decisive (see MatchingOptions); `needed` gets the lead it needs.
  bool decisive(const Distinction& d, double* needed = nullptr) const;
  // Refines B_T_M by least squares over a verification's correspondences.
  Eigen::Vector3d refine(const MatchInput& input, const Verification& verification) const;
  // The answer moved to where the most plan walls agree (each direction's walls vote, within
  // deviation_distance, how far it should move along their normal), if that is at least
  // consensus_min_walls more than at the answer; else the answer. Its yaw is kept.
  Verification consensus(const MatchInput& input, const Verification& answer) const;
  // How many plan walls the S-planes put on their surfaces at x_y_yaw, each counted once by the
  // best fit of its S-planes (exp(−½(e/plane_sigma)²)).
  double wallsAgreeing(const MatchInput& input, const Eigen::Vector3d& x_y_yaw) const;

  const bim::AGraph& graph() const { return *graph_; }
  const MatchingOptions& options() const { return options_; }

 private:
  struct Cell {
    std::vector<int> surfaces;
    std::vector<int> rooms;
  };
  // A wall corner of the plan: two exposed surface segments meeting within corner_gap.
  struct Corner {
    Eigen::Vector2d point = Eigen::Vector2d::Zero();  // where the two walls' lines cross
    std::array<double, 2> normal_yaw{};               // each wall's normal
    std::array<Eigen::Vector2d, 2> arm_direction;     // from the corner along each wall
    std::array<double, 2> arm{};                      // m of wall along each arm
  };
  // The corners two walls (S-planes or A-surface segments) make: their ends within corner_gap
  // of the crossing of their lines, normals at least min_corner_angle_deg apart (`min_sine`
  // is its sine).
  static std::optional<Corner> cornerOf(const bim::Plane& p, Eigen::Vector2d p_start,
                                        Eigen::Vector2d p_end, const bim::Plane& q,
                                        Eigen::Vector2d q_start, Eigen::Vector2d q_end, double gap,
                                        double min_sine);
  const Cell* cellAt(const Eigen::Vector2d& p) const;
  // Construction, step by step: the grid over the plan's surfaces and rooms, the cells a box
  // (a–b grown by `pad`) covers, the surfaces and the rooms entered in the grid, the plan's
  // wall corners.
  void layGrid();
  std::vector<Cell*> cellsNear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double pad);
  void indexSurfaces();
  void indexRoomsAndDoors();
  void findCorners();
  int matchRoom(const MatchRoom& room, const Placement& placed, double* distance) const;
  int matchPlane(const MatchPlane& plane, const Placement& placed, double* overlap,
                 double* distance) const;
  // How far the segment a–b (in P) runs along the surface's exposed parts, and whether it reaches
  // them: it overlaps one, or falls short of one by at most plane_gap. A plane that does not reach
  // a surface is not that surface, however close to its line (a wall further along).
  struct Reach {
    double shared = 0.0;  // m of overlap, summed over the exposed parts
    bool reaches = false;
  };
  Reach reachOf(int surface, const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // Whether the S-plane, placed by x_y_yaw, lies as a wall built off a plan surface would
  // (deviation_distance, deviation_angle_deg).
  bool nearAsBuiltOff(const MatchPlane& plane, const Placement& placed) const;
  // Seeds (slam/isgraph/match_seeds.cpp): the B_T_M each kind of local structure proposes.
  void seedFromFourWallRooms(const MatchInput& input, std::vector<Eigen::Vector3d>& out) const;
  void seedFromCorridors(const MatchInput& input, std::vector<Eigen::Vector3d>& out) const;
  void seedFromCorners(const MatchInput& input, std::vector<Eigen::Vector3d>& out) const;
  // Verifies, clusters and refines the hypotheses, then decides.
  MatchResult evaluate(const MatchInput& input, const std::vector<Eigen::Vector3d>& hypotheses,
                       ThreadPool* pool = nullptr) const;
  // verify() without `built_off_length` (left 0) when `built_off` is false: the score, sort and
  // clusters of a match's many hypotheses do not read it, and it was a sixth of their cost; the
  // few answers that reach the result are verified whole.
  Verification verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw,
                      bool built_off) const;
  // Decision (slam/isgraph/match_decision.cpp): support, adequacy, then decisive evidence.
  void decide(const MatchInput& input, MatchResult& result) const;
  // The decision's account of the best answer's evidence (MatchResult::reason's first part).
  std::string evidenceText(const MatchInput& input, const MatchResult& result,
                           const std::set<int>& a_rooms, int planes_outside,
                           int rooms_explained) const;
  std::vector<std::string> separatingRooms(const Eigen::Vector3d& best,
                                           const Eigen::Vector3d& other) const;
  bool joinedByDoor(int a, int b) const;

 public:
  // Whether an S-plane, seen from B_T_M, lies within `angle_deg` and `distance` of an A-surface
  // (its normal and the distance of the S-plane's middle to the surface's plane).
  bool planeAgrees(const MatchPlane& plane, int surface, const Placement& placed, double angle_deg,
                   double distance) const;

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
  // Each surface's normal as a unit vector in the plane, and the cosine of the plane angle
  // tolerance less a margin: matchPlane's screen, which passes every surface the exact angle test
  // would pass (the margin is ten million times the rounding of a dot product of unit vectors).
  std::vector<Eigen::Vector2d> surface_direction_;
  double plane_angle_screen_ = -2.0;  // no screen (a tolerance of 90° or more)
  // Each surface's plan wall, as the index of that wall's first surface (a flight's face: its
  // own index): both faces of a wall are one wall.
  std::vector<int> wall_of_surface_;
  std::vector<double> room_yaw_;  // yaw of each room's first pair normal
  std::vector<std::vector<int>> doors_of_room_;
  std::vector<Corner> corners_;
};

}  // namespace isg::slam
