#include "eval/association.hpp"

#include <algorithm>
#include <cmath>

namespace isg::eval {

namespace {

// Index of the nearest stamp (the first among equals), by binary search when sorted.
int nearest(const common::Trajectory& t, double stamp, bool sorted) {
  if (!sorted) {
    int best = 0;
    for (int i = 1; i < int(t.size()); ++i) {
      if (std::abs(t[i].t - stamp) < std::abs(t[best].t - stamp)) best = i;
    }
    return best;
  }
  const auto it = std::lower_bound(t.begin(), t.end(), stamp,
                                   [](const common::StampedPose& p, double s) { return p.t < s; });
  int i = int(it - t.begin());
  if (i == int(t.size())) return i - 1;
  // On a tie the earlier stamp wins, as numpy's argmin picks the first minimum.
  if (i > 0 && std::abs(t[i - 1].t - stamp) <= std::abs(t[i].t - stamp)) {
    i = i - 1;
    while (i > 0 && t[i - 1].t == t[i].t) --i;  // duplicates: the first of them
  }
  return i;
}

}  // namespace

Association associate(const common::Trajectory& reference, const common::Trajectory& estimate,
                      double max_diff) {
  Association out;
  if (reference.empty() || estimate.empty()) return out;
  const bool reference_shorter = reference.size() < estimate.size();
  const common::Trajectory& shorter = reference_shorter ? reference : estimate;
  const common::Trajectory& longer = reference_shorter ? estimate : reference;
  const bool sorted = std::is_sorted(
      longer.begin(), longer.end(),
      [](const common::StampedPose& a, const common::StampedPose& b) { return a.t < b.t; });
  for (int i = 0; i < int(shorter.size()); ++i) {
    const int j = nearest(longer, shorter[i].t, sorted);
    if (std::abs(longer[j].t - shorter[i].t) > max_diff) continue;
    out.reference.push_back(reference_shorter ? i : j);
    out.estimate.push_back(reference_shorter ? j : i);
  }
  return out;
}

}  // namespace isg::eval
