#pragma once

#include <cmath>

namespace isg::worlds {

// A length in metres rounded to the millimetre: generated plans put their coordinates on a
// millimetre grid, so that sides meant to coincide do, and files read back as written.
inline double mm(double metres) { return std::round(metres * 1000.0) / 1000.0; }

}  // namespace isg::worlds
