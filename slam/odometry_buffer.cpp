#include "slam/odometry_buffer.hpp"

#include <algorithm>

namespace isg::slam {

void OdometryBuffer::push(const Odometry& odometry) {
  if (!buffer_.empty() && odometry.stamp <= buffer_.back().stamp) return;  // out of order: ignore
  buffer_.push_back(odometry);
  while (buffer_.size() > 2 && buffer_.front().stamp < odometry.stamp - keep_) buffer_.pop_front();
}

std::optional<Eigen::Isometry3d> OdometryBuffer::at(double t) const {
  if (buffer_.empty() || t < buffer_.front().stamp || t > buffer_.back().stamp) return std::nullopt;
  const auto it = std::lower_bound(buffer_.begin(), buffer_.end(), t,
                                   [](const Odometry& o, double s) { return o.stamp < s; });
  if (it->stamp == t || it == buffer_.begin()) return it->M_T_R;
  const Odometry& a = *(it - 1);
  const Odometry& b = *it;
  const double w = (t - a.stamp) / (b.stamp - a.stamp);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = (1 - w) * a.M_T_R.translation() + w * b.M_T_R.translation();
  out.linear() = Eigen::Quaterniond(a.M_T_R.linear())
                     .slerp(w, Eigen::Quaterniond(b.M_T_R.linear()))
                     .toRotationMatrix();
  return out;
}

int deskew(Scan& scan, const OdometryBuffer& odometry, const Eigen::Isometry3d& R_T_L) {
  const auto at_stamp = odometry.at(scan.stamp);
  if (!at_stamp) return int(scan.points.size());
  const Eigen::Isometry3d L0_T_M = (*at_stamp * R_T_L).inverse();
  int missed = 0;
  for (auto& p : scan.points) {
    const auto at_point = odometry.at(scan.stamp + p.time);
    if (!at_point) {
      ++missed;
      continue;
    }
    const Eigen::Vector3d q = L0_T_M * (*at_point * R_T_L) * Eigen::Vector3d(p.x, p.y, p.z);
    p.x = float(q.x());
    p.y = float(q.y());
    p.z = float(q.z());
  }
  return missed;
}

}  // namespace isg::slam
