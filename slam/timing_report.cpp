#include "slam/timing_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isg::slam {

namespace {

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const std::size_t i =
      std::min(v.size() - 1, std::size_t(std::ceil(q * v.size())) - (q > 0 ? 1 : 0));
  return v[i];
}

}  // namespace

std::vector<TimingAt> timingAt(const std::vector<KeyframeTiming>& timings,
                               const std::vector<int>& sizes, int half_width) {
  std::vector<TimingAt> out;
  for (int n : sizes) {
    const int lo = std::max(0, n - half_width), hi = std::min(int(timings.size()), n + half_width);
    if (hi - lo < 5) continue;
    std::vector<double> extraction, planes, optimisation;
    for (int k = lo; k < hi; ++k) {
      extraction.push_back(1e3 * timings[k].extraction_s);
      planes.push_back(1e3 * timings[k].planes_s);
      optimisation.push_back(1e3 * timings[k].optimisation_s);
    }
    TimingAt row;
    row.keyframes = n;
    row.samples = hi - lo;
    row.extraction_median_ms = percentile(extraction, 0.5);
    row.extraction_p95_ms = percentile(extraction, 0.95);
    row.planes_median_ms = percentile(planes, 0.5);
    row.planes_p95_ms = percentile(planes, 0.95);
    row.optimisation_median_ms = percentile(optimisation, 0.5);
    row.optimisation_p95_ms = percentile(optimisation, 0.95);
    out.push_back(row);
  }
  return out;
}

std::string formatTiming(const std::vector<TimingAt>& rows) {
  std::string out;
  char line[256];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line,
                  "  at %4d keyframes: front end (deskew, registration, planes, association) "
                  "median %.1f ms, p95 %.1f ms, of which planes median %.1f ms, p95 %.1f ms; "
                  "optimisation, merging and rooms median %.1f ms, p95 %.1f ms\n",
                  r.keyframes, r.extraction_median_ms, r.extraction_p95_ms, r.planes_median_ms,
                  r.planes_p95_ms, r.optimisation_median_ms, r.optimisation_p95_ms);
    out += line;
  }
  return out;
}

}  // namespace isg::slam
