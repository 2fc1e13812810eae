#pragma once

#include <optional>
#include <string_view>

namespace isg::slam {

// Where a global localizer's search for its place in the plan stands (docs/matching.md). Typed
// through the Localizer interface and the run's metrics; spelled as words only in JSON and text.
// kLost: was matched, then the world stopped agreeing with the graph; a fresh S-Graph segment is
// being matched again.
enum class MatchStatus { kNotYet, kAmbiguous, kMatched, kContradicted, kLost };

// "not yet", "ambiguous", "matched", "contradicted", "lost": metrics.json's spelling.
const char* toString(MatchStatus status);
// The status a word names, or nullopt for any other text.
std::optional<MatchStatus> matchStatusFromString(std::string_view text);

}  // namespace isg::slam
