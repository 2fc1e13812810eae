#include "eval/wrong_localization.hpp"

#include <algorithm>
#include <cmath>

#include "eval/association.hpp"

namespace isg::eval {

WrongLocalization wrongLocalization(common::PoseSequence ground_truth,
                                    common::PoseSequence estimate,
                                    const WrongLocalizationOptions& options) {
  WrongLocalization out;
  if (ground_truth.empty() || estimate.empty()) return out;
  const Association pairs = associate(ground_truth, estimate, options.max_diff);
  // Associated rows in the estimate's time order, each with its 2D and its height error.
  struct Row {
    double t;
    double error;
    double height_error;
  };
  std::vector<Row> rows;
  rows.reserve(pairs.estimate.size());
  for (std::size_t i = 0; i < pairs.estimate.size(); ++i) {
    const common::StampedPose e = estimate[pairs.estimate[i]];
    const common::StampedPose g = ground_truth[pairs.reference[i]];
    const Eigen::Vector3d d = e.pose.translation() - g.pose.translation();
    rows.push_back({e.t, d.head<2>().norm(), std::abs(d.z())});
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.t < b.t; });
  double stretch_start = 0.0;
  bool in_stretch = false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out.max_error = std::max(out.max_error, rows[i].error);
    out.max_height_error = std::max(out.max_height_error, rows[i].height_error);
    const bool off =
        rows[i].error > options.max_error || rows[i].height_error > options.max_height_error;
    const bool continues = in_stretch && off && rows[i].t - rows[i - 1].t <= options.max_gap;
    if (continues) {
      out.seconds += rows[i].t - rows[i - 1].t;
    } else if (off) {
      stretch_start = rows[i].t;
    }
    in_stretch = off;
    if (!off) continue;
    const double length = rows[i].t - stretch_start;
    out.longest = std::max(out.longest, length);
    if (length > options.max_duration && !out.first_wrong_at) out.first_wrong_at = stretch_start;
  }
  out.wrong = out.longest > options.max_duration;
  return out;
}

}  // namespace isg::eval
