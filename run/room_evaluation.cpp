#include "run/room_evaluation.hpp"

#include <algorithm>
#include <cmath>

#include "bim/agraph.hpp"
#include "bim/polygon.hpp"

namespace isg::run {

RoomDetectionReport evaluateRooms(const bim::Plan& plan, const std::string& level_id,
                                  const std::vector<slam::MapRoom>& rooms,
                                  common::PoseSequence ground_truth,
                                  const eval::Similarity& B_from_M, double tolerance) {
  RoomDetectionReport report;
  const bim::AGraph agraph = bim::buildAGraph(plan);
  for (const auto& room : agraph.rooms) {
    // The S-Graph's rooms are four-wall rooms and corridors: a plan room of another shape (an
    // L-shaped hall) cannot be found as one, and is left out of the measure.
    if (room.level != level_id || room.kind == bim::RoomKind::kPolygon) continue;
    const bool walked = std::any_of(ground_truth.begin(), ground_truth.end(), [&](const auto& p) {
      return bim::containsPoint(room.outline, p.pose.translation().template head<2>());
    });
    if (!walked) continue;
    report.walked.push_back(room.id);
    std::vector<double> plan_widths = room.widths;
    std::sort(plan_widths.begin(), plan_widths.end());
    double best = 1e9;
    for (const auto& s : rooms) {
      const Eigen::Vector3d centre_M(s.centre.x(), s.centre.y(), 0.0);
      const Eigen::Vector2d centre_B = B_from_M.apply(centre_M).head<2>();
      if (!bim::containsPoint(room.outline, centre_B)) continue;
      double error = 1e9;
      if (s.four_wall && plan_widths.size() == 2) {
        std::array<double, 2> w = s.widths;
        std::sort(w.begin(), w.end());
        error = std::max(std::abs(w[0] - plan_widths[0]), std::abs(w[1] - plan_widths[1]));
      } else if (!s.four_wall && !plan_widths.empty()) {
        error = std::abs(s.widths[0] - plan_widths[0]);
      }
      best = std::min(best, error);
    }
    if (best <= tolerance) {
      report.detected.push_back(room.id);
      report.worst_width_error = std::max(report.worst_width_error, best);
    }
  }
  return report;
}

}  // namespace isg::run
