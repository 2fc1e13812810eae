#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "bim/camera_models.hpp"
#include "sim/renderer.hpp"

namespace isg::sim {

// A fisheye lens rendered through a cube map: MuJoCo draws pinhole views of 90° (the front and
// the four sides: a lens of up to 135° from its axis never needs the back) from the lens's
// centre, and each pixel of the fisheye image takes the colour its ray meets there
// (bim::pixelRay, bilinear between the face's four nearest pixels). The faces are sampled at
// about the lens's own resolution at its centre (2 × its focal length across a face).
class FisheyeCamera {
 public:
  // `model` must have a fisheye lens. Surfaces textured from `seed`.
  FisheyeCamera(const mjModel& world, const bim::CameraModel& model, std::uint64_t seed);

  // The image of the lens at B_T_C (its optical frame), black outside its image circle. When
  // `range` is given it receives each pixel's distance along its ray, metres (0 outside the
  // circle or where nothing lies within `far_m`).
  Image render(mjData& data, const Eigen::Isometry3d& B_T_C, double far_m,
               std::vector<float>* range);

  int faceSize() const { return face_size_; }

 private:
  static constexpr int kFaces = 5;
  struct Sample {
    std::int8_t face = -1;  // -1: outside the image circle
    float u = 0.0f, v = 0.0f;
    float range_per_depth = 0.0f;  // the ray's length per unit of the face's depth
  };
  bim::CameraModel model_;
  int face_size_;
  Renderer renderer_;
  std::array<Eigen::Matrix3d, kFaces> C_R_face_;
  std::vector<Sample> samples_;
};

}  // namespace isg::sim
