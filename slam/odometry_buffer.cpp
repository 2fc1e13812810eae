#include "slam/odometry_buffer.hpp"

#include <algorithm>
#include <cmath>

namespace isg::slam {

void OdometryBuffer::push(const sensors::Odometry& odometry) {
  if (!buffer_.empty() && odometry.stamp <= buffer_.back().stamp) return;  // out of order: ignore
  buffer_.push_back(odometry);
  while (buffer_.size() > 2 && buffer_.front().stamp < odometry.stamp - keep_) buffer_.pop_front();
}

std::optional<Eigen::Isometry3d> OdometryBuffer::at(double t) const {
  if (buffer_.empty() || t < buffer_.front().stamp || t > buffer_.back().stamp) return std::nullopt;
  const auto it =
      std::lower_bound(buffer_.begin(), buffer_.end(), t,
                       [](const sensors::Odometry& o, double s) { return o.stamp < s; });
  if (it->stamp == t || it == buffer_.begin()) return it->M_T_R;
  const sensors::Odometry& a = *(it - 1);
  const sensors::Odometry& b = *it;
  const double w = (t - a.stamp) / (b.stamp - a.stamp);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = (1 - w) * a.M_T_R.translation() + w * b.M_T_R.translation();
  out.linear() = Eigen::Quaterniond(a.M_T_R.linear())
                     .slerp(w, Eigen::Quaterniond(b.M_T_R.linear()))
                     .toRotationMatrix();
  return out;
}

int deskew(sensors::Scan& scan, const OdometryBuffer& odometry, const Eigen::Isometry3d& R_T_L) {
  const auto at_stamp = odometry.at(scan.stamp);
  if (!at_stamp) return int(scan.points.size());
  const Eigen::Isometry3d L0_T_M = (*at_stamp * R_T_L).inverse();
  // L0_T_L(t) exactly every kStep, linearly in between: within 0.5 ms the sensor turns by under
  // 1e-3 rad, so the interpolated rotation departs from the exact one by under 1e-7 (a micrometre
  // at 10 m); a point whose neighbouring samples are not both covered is deskewed exactly.
  constexpr double kStep = 0.5e-3;
  // Points' times about the stamp: from 0 when the stamp is the first firing, negative before a
  // stamp taken later in the turn (the ROS 1 driver's: its last packet).
  double first = 0.0, span = 0.0;
  for (const auto& p : scan.points) first = std::min(first, double(p.time));
  for (const auto& p : scan.points) span = std::max(span, double(p.time) - first);
  const int samples = int(std::ceil(span / kStep)) + 2;
  std::vector<Eigen::Matrix3d> rotations(samples);
  std::vector<Eigen::Vector3d> translations(samples);
  std::vector<char> covered(samples, 0);
  for (int j = 0; j < samples; ++j) {
    if (const auto at = odometry.at(scan.stamp + first + j * kStep)) {
      const Eigen::Isometry3d L0_T_L = L0_T_M * (*at * R_T_L);
      rotations[j] = L0_T_L.linear();
      translations[j] = L0_T_L.translation();
      covered[j] = 1;
    }
  }
  int missed = 0;
  for (auto& p : scan.points) {
    const double t = std::max(0.0, double(p.time) - first);
    const int j = std::min(samples - 2, int(t / kStep));
    const Eigen::Vector3d v(p.x, p.y, p.z);
    Eigen::Vector3d q;
    if (covered[j] && covered[j + 1]) {
      const double a = t / kStep - j;
      q = rotations[j] * v + a * ((rotations[j + 1] - rotations[j]) * v) + translations[j] +
          a * (translations[j + 1] - translations[j]);
    } else {
      const auto at_point = odometry.at(scan.stamp + p.time);
      if (!at_point) {
        ++missed;
        continue;
      }
      q = L0_T_M * (*at_point * R_T_L) * v;
    }
    p.x = float(q.x());
    p.y = float(q.y());
    p.z = float(q.z());
  }
  return missed;
}

}  // namespace isg::slam
