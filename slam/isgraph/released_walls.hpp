#pragma once

#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/wall_release.hpp"

namespace isg::slam {

// The plan walls released from the merge under the answer held now (docs/matching.md, "An
// imprecise plan"): each held wall judged against the others on every keyframe, released after
// `strikes` judgements in a row beyond the thresholds, and never matched again under that
// answer where it was seen off: its S-plane, and its surface along the stretch that S-plane
// covered (a plane of the S-Graph reaches at most AssociationOptions::max_length along its wall;
// a long wall is judged and released a stretch at a time). A new answer starts with none.
class ReleasedWalls {
 public:
  struct Release {
    double stamp = 0.0;
    int plane = -1;                    // S-plane
    int surface = -1;                  // A-surface
    double offset = 0.0, angle = 0.0;  // the residual that released it (m, rad)
    // The stretch of the surface released: the S-plane's seen segment, in P.
    Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  };

  explicit ReleasedWalls(const WallReleaseOptions& options) : options_(options) {}

  // Judges `walls` (with their (S-plane, A-surface) in `held`, heldWalls) and releases those
  // beyond the thresholds on `strikes_needed` judgements in a row: they leave `plane_matches`.
  // Unless most of the judged walls are due: that is an answer off the building, not a building
  // off its plan, and for the hold gate and the contradiction check to settle.
  void judge(const std::vector<HeldWall>& walls, const std::vector<std::pair<int, int>>& held,
             double stamp, int strikes_needed, std::map<int, int>& plane_matches);
  // Whether a correspondence may be made: its S-plane was not released, nor its surface along
  // the S-plane's seen segment (ends in P, under the answer held), within
  // WallReleaseOptions::stretch_margin.
  bool allows(int plane, int surface, const Eigen::Vector2d& start_in_P,
              const Eigen::Vector2d& end_in_P) const;
  // The offset that released a surface (the latest), along its normal: how far the wall stands off
  // the plan, which moves its rooms' centres by half as much. None when it is held.
  std::optional<double> offsetOf(int surface) const;
  // The answer moved (its walls were judged under the old one): the releases of these S-planes
  // are undone (the log keeps them), and their strikes forgotten.
  void reopen(const std::vector<MatchPlane>& planes);
  // A new answer, or none: nothing released.
  void clear();
  // Every release, in order, for the log.
  const std::vector<Release>& log() const { return log_; }

 private:
  WallReleaseOptions options_;
  std::vector<Release> log_;
  std::set<int> planes_;                   // released S-planes
  std::map<int, double> surfaces_;         // released A-surface → the offset that released it
  std::multimap<int, Release> stretches_;  // released A-surface → each stretch released
  std::map<int, int> strikes_;             // S-plane → judgements in a row beyond a threshold
};

}  // namespace isg::slam
