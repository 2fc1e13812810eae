#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "slam/isgraph/graph_matching.hpp"
#include "slam/localizer.hpp"
#include "slam/match_status.hpp"

namespace isg::slam {

// What the iS-Graph's matching did over a run, for its status and its log: the status now and
// each change with its reason, the full matching attempts and their times, the latest one's
// result, and how often the answer was contradicted, moved or lost (sgraph.json's "matching").
class MatchLog {
 public:
  // The answer moved to where more plan walls agree (the localizer's moveToConsensus).
  struct AnswerMove {
    double stamp = 0.0;
    double distance = 0.0;                         // m, at the middle of the map
    double walls_before = 0.0, walls_after = 0.0;  // GraphMatcher::wallsAgreeing
  };
  // A unique answer elsewhere on the whole map that the recent walls refused: the map bent, the
  // answer held where the robot is (the localizer's checkForContradiction).
  struct RefusedContradiction {
    double stamp = 0.0;
    double distance = 0.0;  // m, between the answers at the middle of the map
    std::string reason;     // the recent walls' lead for the answer held
  };

  // A status at a keyframe, with why; a repeat of the status now is not a change.
  void record(double stamp, int keyframe, MatchStatus status, const std::string& reason);
  // A full matching attempt: its time, and its result (in B) as the latest.
  void attempted(const MatchResult& result_in_B);
  void contradicted() { ++contradictions_; }
  void lost() { ++losses_; }
  void moved(const AnswerMove& move) { answer_moves_.push_back(move); }
  void refused(const RefusedContradiction& refusal) { refusals_.push_back(refusal); }
  // A floor-wide move the recent walls disagreed with (ISGraphOptions::move_hold_walls).
  void moveRefused() { ++moves_refused_; }

  MatchStatus status() const { return status_; }
  const std::vector<StatusChange>& events() const { return events_; }
  const std::optional<MatchResult>& lastMatch() const { return last_match_; }
  const std::vector<double>& matchingTimes() const { return matching_times_; }

  // Its part of sgraph.json's "matching": status, contradictions, contradictions_refused,
  // answer_moves, answer_moves_refused, times_lost, events and last_match.
  void addTo(nlohmann::json& matching) const;

 private:
  MatchStatus status_ = MatchStatus::kNotYet;
  std::vector<StatusChange> events_;
  std::optional<MatchResult> last_match_;  // in B
  std::vector<double> matching_times_;
  int contradictions_ = 0;
  int losses_ = 0;
  std::vector<AnswerMove> answer_moves_;
  std::vector<RefusedContradiction> refusals_;
  int moves_refused_ = 0;
};

}  // namespace isg::slam
