#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace isg::common {

// "1 door", "0 doors", "3 doors": a count and its noun, for the summaries people read. `plural`
// for nouns that do not take an s ("body", "bodies").
inline std::string counted(std::uint64_t n, const std::string& singular,
                           const std::string& plural = "") {
  return std::to_string(n) + " " + (n == 1 ? singular : plural.empty() ? singular + "s" : plural);
}

// "R1, R2, R3" or, past `shown` names, "R1, …, R10 and 596 more (606 in all)": a list of ids a
// message names, short enough to read however many there are.
inline std::string namedList(const std::vector<std::string>& names, std::size_t shown = 10) {
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < shown; ++i) {
    if (i > 0) text += ", ";
    text += names[i];
  }
  if (names.size() > shown) {
    text += " and " + std::to_string(names.size() - shown) + " more (" +
            std::to_string(names.size()) + " in all)";
  }
  return text;
}

}  // namespace isg::common
