#pragma once

#include <Eigen/Core>
#include <optional>

#include "bim/camera_models.hpp"

namespace isg::bim {

// Where a point of the camera's optical frame (z forward, x right, y down) lands in its image
// (pixel centres at whole numbers); nullopt behind a pinhole or beyond a fisheye's image circle.
std::optional<Eigen::Vector2d> projectToPixel(const CameraModel& camera,
                                              const Eigen::Vector3d& p_C);

// The unit ray of the optical frame that pixel (u, v) looks along; nullopt where the pixel
// lies outside a fisheye's image circle.
std::optional<Eigen::Vector3d> pixelRay(const CameraModel& camera, const Eigen::Vector2d& uv);

// θd of the equidistant model for θ, and θ for θd (Newton's method: the polynomial rises
// monotonically over the lens's angles); radians.
double equidistantDistort(const FisheyeLens& lens, double theta);
double equidistantUndistort(const FisheyeLens& lens, double theta_d);

}  // namespace isg::bim
