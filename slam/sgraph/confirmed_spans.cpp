#include "slam/sgraph/confirmed_spans.hpp"

#include <algorithm>
#include <cmath>

namespace isg::slam {

// Where the wall ends, the dozens of observations that saw it up to there end together; one or
// two that ran past it (a ragged region at a free end, a keyframe a few degrees off) are strays
// beside them, and would stretch a union or a count of two. A share of all the observations would
// not do: each part of a 30 m wall is seen by a few of its hundred. So the share is of the most
// nearby (ConfirmationOptions says how near, and why no nearer than the progress report's gap).
std::vector<std::pair<double, double>> confirmedSpans(
    const MapPlane& m, const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& spans,
    const ConfirmationOptions& options) {
  std::vector<std::pair<double, double>> out;
  const Eigen::Vector2d direction = m.end - m.start;
  const double length = direction.norm();
  if (length < 1e-9 || spans.empty()) return out;
  const Eigen::Vector2d axis = direction / length;
  std::vector<std::pair<double, int>> events;  // (position along, +1 a span opens / −1 closes)
  std::vector<double> opens, closes;
  for (const auto& [a, b] : spans) {
    double s0 = (a - m.start).dot(axis), s1 = (b - m.start).dot(axis);
    if (s0 > s1) std::swap(s0, s1);
    opens.push_back(std::clamp(s0, 0.0, length));
    closes.push_back(std::clamp(s1, 0.0, length));
    events.push_back({opens.back(), +1});
    events.push_back({closes.back(), -1});
  }
  std::sort(events.begin(), events.end());
  // How many spans cover each stretch between consecutive ends.
  struct Stretch {
    double from, to;
    int covering;
  };
  std::vector<Stretch> stretches;
  int covering = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    covering += events[i].second;
    if (i + 1 < events.size() && events[i + 1].first > events[i].first) {
      stretches.push_back({events[i].first, events[i + 1].first, covering});
    }
  }
  const int least = m.observations <= 1 ? 1 : 2;  // a span each, or one each of its pieces
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const Stretch& here = stretches[i];
    if (here.covering < least) continue;
    // Not within near_m of a stretch seen by so many more that this one's are a few strays.
    const auto outnumbers = [&](const Stretch& other) {
      return here.covering < int(std::ceil(options.share * other.covering));
    };
    double from = here.from, to = here.to;
    for (std::size_t j = i; j-- > 0 && stretches[j].to >= here.from - options.near_m;) {
      if (outnumbers(stretches[j])) from = std::max(from, stretches[j].to + options.near_m);
    }
    for (std::size_t j = i + 1;
         j < stretches.size() && stretches[j].from <= here.to + options.near_m; ++j) {
      if (outnumbers(stretches[j])) to = std::min(to, stretches[j].from - options.near_m);
    }
    if (to <= from) continue;
    if (!out.empty() && out.back().second >= from) {
      out.back().second = to;
    } else {
      out.push_back({from, to});
    }
  }
  // The share above puts an end where only a fifth of the observations that saw the part to its
  // end still reach: an outer quantile of their ends, which their keyframes' errors spread by a
  // few centimetres, so each edge of a gap lay that much into it. The end is the median of the
  // ends within near_m of it (the strays past it among them), never further out than the share.
  std::sort(opens.begin(), opens.end());
  std::sort(closes.begin(), closes.end());
  const auto medianNear = [&](const std::vector<double>& ends, double at) {
    const auto first = std::lower_bound(ends.begin(), ends.end(), at - options.near_m);
    const auto last = std::upper_bound(ends.begin(), ends.end(), at + options.near_m);
    const auto n = last - first;
    if (n == 0) return at;
    return 0.5 * (*(first + (n - 1) / 2) + *(first + n / 2));
  };
  for (auto& [from, to] : out) {
    const double inner_from = std::clamp(medianNear(opens, from), from, to);
    const double inner_to = std::clamp(medianNear(closes, to), inner_from, to);
    from = inner_from;
    to = inner_to;
  }
  return out;
}

}  // namespace isg::slam
