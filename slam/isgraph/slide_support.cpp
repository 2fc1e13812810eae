#include "slam/isgraph/slide_support.hpp"

#include <algorithm>

namespace isg::slam {

void keepBestSupported(std::vector<Eigen::Vector3d>& hypotheses,
                       const std::vector<std::pair<int, double>>& slides,
                       std::vector<SlideProposal> proposals, std::size_t keep, double tolerance) {
  if (hypotheses.size() <= keep) return;
  // Ordered by turn, then by slide: a turn's proposals within the tolerance are then one run.
  const auto before = [](const SlideProposal& a, const SlideProposal& b) {
    return a.turn != b.turn ? a.turn < b.turn : a.slide < b.slide;
  };
  std::sort(proposals.begin(), proposals.end(), before);
  std::vector<double> prefix(proposals.size() + 1, 0.0);  // lengths summed in that order
  for (std::size_t k = 0; k < proposals.size(); ++k) {
    prefix[k + 1] = prefix[k] + proposals[k].length;
  }
  std::vector<double> support(hypotheses.size());
  for (std::size_t j = 0; j < hypotheses.size(); ++j) {
    const auto [turn, slide] = slides[j];
    const auto lo = std::lower_bound(proposals.begin(), proposals.end(),
                                     SlideProposal{turn, slide - tolerance, 0.0}, before);
    const auto hi =
        std::upper_bound(lo, proposals.end(), SlideProposal{turn, slide + tolerance, 0.0}, before);
    support[j] = prefix[hi - proposals.begin()] - prefix[lo - proposals.begin()];
  }
  std::vector<std::size_t> order(hypotheses.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return support[a] > support[b]; });
  std::vector<bool> kept(hypotheses.size(), false);
  for (std::size_t k = 0; k < keep; ++k) kept[order[k]] = true;
  std::size_t next = 0;
  for (std::size_t j = 0; j < hypotheses.size(); ++j) {
    if (kept[j]) hypotheses[next++] = hypotheses[j];
  }
  hypotheses.resize(next);
}

}  // namespace isg::slam
