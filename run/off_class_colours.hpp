#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>

#include "slam/deviations/map_against_plan.hpp"

namespace isg::run {

// The colours of slam::offClass's four classes, one table for every picture (deviations.svg, the
// run's MCAP): green within 2 cm, yellow to 4 cm, orange to 8 cm, red beyond.
inline constexpr std::array<std::array<std::uint8_t, 3>, 4> kOffClassRgb = {
    {{26, 152, 80}, {217, 184, 0}, {244, 109, 67}, {192, 24, 24}}};

// "#1a9850": a class's colour as SVG writes it.
inline std::string offClassHex(int off_class) {
  const auto& rgb = kOffClassRgb[std::size_t(off_class)];
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return text;
}

}  // namespace isg::run
