#pragma once

#include <cstdint>
#include <string>

namespace isg::common {

// "1 door", "0 doors", "3 doors": a count and its noun, for the summaries people read. `plural`
// for nouns that do not take an s ("body", "bodies").
inline std::string counted(std::uint64_t n, const std::string& singular,
                           const std::string& plural = "") {
  return std::to_string(n) + " " + (n == 1 ? singular : plural.empty() ? singular + "s" : plural);
}

}  // namespace isg::common
