#pragma once

#include "bim/synthetic_plan.hpp"

namespace isg::bim::bench {

// A grid plan of about `rooms` rooms for the benchmarks: 5 rows up to 200 rooms, 10 up to 1000,
// 20 from there.
inline GridPlanSpec gridOf(int rooms) {
  GridPlanSpec spec;
  spec.rows = rooms >= 1000 ? 20 : (rooms >= 200 ? 10 : 5);
  spec.cols = rooms / spec.rows;
  return spec;
}

}  // namespace isg::bim::bench
