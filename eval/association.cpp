#include "eval/association.hpp"

#include <algorithm>
#include <cmath>

namespace isg::eval {

namespace {

// Index of the nearest stamp (the first among equals), by binary search when sorted.
int nearest(const common::PoseSequence& t, double stamp, bool sorted) {
  if (!sorted) {
    int best = 0;
    for (int i = 1; i < int(t.size()); ++i) {
      if (std::abs(t.time(i) - stamp) < std::abs(t.time(best) - stamp)) best = i;
    }
    return best;
  }
  int i = int(t.lowerBound(stamp));
  if (i == int(t.size())) return i - 1;
  // On a tie the earlier stamp wins, as numpy's argmin picks the first minimum.
  if (i > 0 && std::abs(t.time(i - 1) - stamp) <= std::abs(t.time(i) - stamp)) {
    i = i - 1;
    while (i > 0 && t.time(i - 1) == t.time(i)) --i;  // duplicates: the first of them
  }
  return i;
}

}  // namespace

Association associate(common::PoseSequence reference, common::PoseSequence estimate,
                      double max_diff) {
  Association out;
  if (reference.empty() || estimate.empty()) return out;
  const bool reference_shorter = reference.size() < estimate.size();
  const common::PoseSequence& shorter = reference_shorter ? reference : estimate;
  const common::PoseSequence& longer = reference_shorter ? estimate : reference;
  bool sorted = true;
  for (std::size_t i = 1; i < longer.size() && sorted; ++i) {
    sorted = !(longer.time(i) < longer.time(i - 1));
  }
  for (int i = 0; i < int(shorter.size()); ++i) {
    const int j = nearest(longer, shorter.time(i), sorted);
    if (std::abs(longer.time(j) - shorter.time(i)) > max_diff) continue;
    out.reference.push_back(reference_shorter ? i : j);
    out.estimate.push_back(reference_shorter ? j : i);
  }
  return out;
}

}  // namespace isg::eval
