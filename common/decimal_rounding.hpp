#pragma once

#include <cmath>

namespace isg::common {

// x·scale rounded to an integer as printf's "%.Nf" rounds x to N decimals (scale = 10^N): the
// exact binary value, ties to even. The integer N = round(x·10^k) is found from the product and
// its exact error (fma); N / scale is then what strtod reads back from that text (IEEE division
// is correctly rounded). Exact while |x|·scale < 2^53.
inline double decimalSteps(double x, double scale) {
  const double p = x * scale;
  double n = std::nearbyint(p);                 // ties to even on p; keeps the sign of zero
  const double error = std::fma(x, scale, -p);  // x·scale = p + error, exactly
  const double rest = p - n;                    // exact; only a half-way p can round wrongly
  if (rest == 0.5 && error > 0) n += 1.0;       // x·scale lies just above the half
  if (rest == -0.5 && error < 0) n -= 1.0;      // just below the negative half
  return n;
}

// x as its text with that many decimals reads back.
inline double decimalRounded(double x, double scale) { return decimalSteps(x, scale) / scale; }

}  // namespace isg::common
