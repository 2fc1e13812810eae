#pragma once

#include <cstdio>
#include <string>

namespace isg::run {

// printf into a string, for summary lines and SVG attributes: at most 511 characters, the rest
// cut off (every pattern of the run's reports is far shorter).
template <typename... Values>
std::string format(const char* pattern, Values... values) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

}  // namespace isg::run
