#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace isg::slam {

// A slide along a corridor, proposed by one S-wall across it of `length` on one A-surface, with
// the corridor turned one way or the other.
struct SlideProposal {
  int turn;
  double slide;
  double length;
};

// Of `hypotheses` (the turn and slide of each in `slides`, in the same order), keeps at most
// `keep`: those with the most proposed wall length within `tolerance` of their slide at the same
// turn; ties go to the earlier. The ones kept stay in their order; none goes when there are no
// more than `keep`. (GraphMatcher's corridor seeds, MatchingOptions::max_corridor_slides.)
void keepBestSupported(std::vector<Eigen::Vector3d>& hypotheses,
                       const std::vector<std::pair<int, double>>& slides,
                       std::vector<SlideProposal> proposals, std::size_t keep, double tolerance);

}  // namespace isg::slam
