#include "bim/camera_projection.hpp"

#include <cmath>

namespace isg::bim {

double equidistantDistort(const FisheyeLens& lens, double theta) {
  const double t2 = theta * theta;
  return theta * (1.0 + t2 * (lens.k[0] + t2 * (lens.k[1] + t2 * (lens.k[2] + t2 * lens.k[3]))));
}

double equidistantUndistort(const FisheyeLens& lens, double theta_d) {
  double theta = theta_d;
  for (int i = 0; i < 20; ++i) {
    const double t2 = theta * theta;
    const double derivative =
        1.0 +
        t2 * (3 * lens.k[0] + t2 * (5 * lens.k[1] + t2 * (7 * lens.k[2] + t2 * 9 * lens.k[3])));
    const double step = (equidistantDistort(lens, theta) - theta_d) / derivative;
    theta -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return theta;
}

std::optional<Eigen::Vector2d> projectToPixel(const CameraModel& camera,
                                              const Eigen::Vector3d& p_C) {
  const PinholeIntrinsics& k = camera.intrinsics;
  if (!camera.fisheye) {
    if (p_C.z() <= 0.0) return std::nullopt;
    return Eigen::Vector2d(k.fx * p_C.x() / p_C.z() + k.cx, k.fy * p_C.y() / p_C.z() + k.cy);
  }
  const double r = std::hypot(p_C.x(), p_C.y());
  const double theta = std::atan2(r, p_C.z());
  if (theta > camera.fisheye->max_angle_rad) return std::nullopt;
  if (r == 0.0) return Eigen::Vector2d(k.cx, k.cy);
  const double scale = equidistantDistort(*camera.fisheye, theta) / r;
  return Eigen::Vector2d(k.fx * scale * p_C.x() + k.cx, k.fy * scale * p_C.y() + k.cy);
}

std::optional<Eigen::Vector3d> pixelRay(const CameraModel& camera, const Eigen::Vector2d& uv) {
  const PinholeIntrinsics& k = camera.intrinsics;
  const double x = (uv.x() - k.cx) / k.fx, y = (uv.y() - k.cy) / k.fy;
  if (!camera.fisheye) return Eigen::Vector3d(x, y, 1.0).normalized();
  const double theta_d = std::hypot(x, y);
  if (theta_d == 0.0) return Eigen::Vector3d::UnitZ();
  // Beyond the lens's last angle the polynomial is not the lens's any more.
  if (theta_d > equidistantDistort(*camera.fisheye, camera.fisheye->max_angle_rad)) {
    return std::nullopt;
  }
  const double theta = equidistantUndistort(*camera.fisheye, theta_d);
  const double s = std::sin(theta) / theta_d;
  return Eigen::Vector3d(s * x, s * y, std::cos(theta));
}

}  // namespace isg::bim
