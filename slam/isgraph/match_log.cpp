#include "slam/isgraph/match_log.hpp"

namespace isg::slam {

void MatchLog::record(double stamp, int keyframe, MatchStatus status, const std::string& reason) {
  if (status == status_ && !events_.empty()) return;
  status_ = status;
  events_.push_back({stamp, keyframe, status, reason});
}

void MatchLog::attempted(const MatchResult& result_in_B) {
  matching_times_.push_back(result_in_B.seconds);
  last_match_ = result_in_B;
}

void MatchLog::addTo(nlohmann::json& matching) const {
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : events_) {
    events.push_back({{"stamp", e.stamp},
                      {"keyframe", e.keyframe},
                      {"status", toString(e.status)},
                      {"reason", e.reason}});
  }
  nlohmann::json moves = nlohmann::json::array();
  for (const auto& m : answer_moves_) {
    moves.push_back({{"stamp", m.stamp},
                     {"moved_m", m.distance},
                     {"walls_agreeing_before", m.walls_before},
                     {"walls_agreeing_after", m.walls_after}});
  }
  nlohmann::json refused = nlohmann::json::array();
  for (const auto& r : refusals_) {
    refused.push_back({{"stamp", r.stamp}, {"apart_m", r.distance}, {"reason", r.reason}});
  }
  matching["status"] = toString(status_);
  matching["contradictions"] = contradictions_;
  matching["contradictions_refused"] = refused;
  matching["answer_moves"] = moves;
  matching["answer_moves_refused"] = moves_refused_;
  matching["times_lost"] = losses_;
  matching["events"] = events;
  if (last_match_) matching["last_match"] = last_match_->toJson();
}

}  // namespace isg::slam
