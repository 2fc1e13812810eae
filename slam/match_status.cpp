#include "slam/match_status.hpp"

#include <array>

namespace isg::slam {

namespace {

constexpr std::array kStatuses = {MatchStatus::kNotYet, MatchStatus::kAmbiguous,
                                  MatchStatus::kMatched, MatchStatus::kContradicted,
                                  MatchStatus::kLost};

}  // namespace

const char* toString(MatchStatus status) {
  switch (status) {
    case MatchStatus::kNotYet:
      return "not yet";
    case MatchStatus::kAmbiguous:
      return "ambiguous";
    case MatchStatus::kMatched:
      return "matched";
    case MatchStatus::kContradicted:
      return "contradicted";
    case MatchStatus::kLost:
      return "lost";
  }
  return "?";
}

std::optional<MatchStatus> matchStatusFromString(std::string_view text) {
  for (const MatchStatus status : kStatuses) {
    if (text == toString(status)) return status;
  }
  return std::nullopt;
}

}  // namespace isg::slam
