#include "sim/fisheye_camera.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bim/camera_projection.hpp"

namespace isg::sim {

namespace {

// Faces about twice the lens's focal length across (a 90° face of N pixels has N/2 pixels per
// unit of tangent at its centre), even, within the world's offscreen buffer.
int faceSizeFor(const bim::CameraModel& model, const mjModel& world) {
  const double focal = std::max(model.intrinsics.fx, model.intrinsics.fy);
  const int size = 2 * int(std::ceil(focal));
  return std::min({size, world.vis.global.offwidth, world.vis.global.offheight});
}

// A 90° square pinhole of `size` pixels.
bim::PinholeIntrinsics faceIntrinsics(int size) {
  return {size, size, 0.5 * size, 0.5 * size, 0.5 * (size - 1), 0.5 * (size - 1)};
}

// The faces' optical frames in the lens's (columns: the face's x, y, z): ahead, right, left,
// down, up.
std::array<Eigen::Matrix3d, 5> faceRotations() {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                        z = Eigen::Vector3d::UnitZ();
  auto frame = [](const Eigen::Vector3d& fx, const Eigen::Vector3d& fy, const Eigen::Vector3d& fz) {
    Eigen::Matrix3d R;
    R.col(0) = fx;
    R.col(1) = fy;
    R.col(2) = fz;
    return R;
  };
  return {frame(x, y, z), frame(-z, y, x), frame(z, y, -x), frame(x, -z, y), frame(x, z, -y)};
}

}  // namespace

FisheyeCamera::FisheyeCamera(const mjModel& world, const bim::CameraModel& model,
                             std::uint64_t seed)
    : model_(model),
      face_size_(faceSizeFor(model, world)),
      renderer_(world, face_size_, face_size_, Renderer::Sampling::kPixelCentres),
      C_R_face_(faceRotations()) {
  if (!model.fisheye) throw std::invalid_argument("FisheyeCamera: the model has no fisheye lens");
  renderer_.enableSurfaceTextures(seed);
  const bim::PinholeIntrinsics& k = model.intrinsics;
  const double f = 0.5 * face_size_, c = 0.5 * (face_size_ - 1);
  samples_.resize(std::size_t(k.width) * k.height);
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const auto ray = bim::pixelRay(model, Eigen::Vector2d(u, v));
      if (!ray) continue;
      // The face the ray leaves the cube through: the largest component along a face's axis.
      int best = 0;
      double best_z = -1.0;
      for (int face = 0; face < kFaces; ++face) {
        const double z = C_R_face_[std::size_t(face)].col(2).dot(*ray);
        if (z > best_z) {
          best_z = z;
          best = face;
        }
      }
      const Eigen::Vector3d d = C_R_face_[std::size_t(best)].transpose() * *ray;
      Sample& s = samples_[std::size_t(v) * k.width + u];
      s.face = std::int8_t(best);
      s.u = float(f * d.x() / d.z() + c);
      s.v = float(f * d.y() / d.z() + c);
      s.range_per_depth = float(1.0 / d.z());
    }
  }
}

Image FisheyeCamera::render(mjData& data, const Eigen::Isometry3d& B_T_C, double far_m,
                            std::vector<float>* range) {
  const bim::PinholeIntrinsics face_k = faceIntrinsics(face_size_);
  std::array<Image, kFaces> faces;
  std::array<std::vector<float>, kFaces> depths;
  for (int face = 0; face < kFaces; ++face) {
    Eigen::Isometry3d B_T_face = B_T_C;
    B_T_face.linear() = B_T_C.linear() * C_R_face_[std::size_t(face)];
    faces[std::size_t(face)] = renderer_.camera(data, B_T_face, face_k, far_m,
                                                range ? &depths[std::size_t(face)] : nullptr);
  }
  const bim::PinholeIntrinsics& k = model_.intrinsics;
  Image image{k.width, k.height, std::vector<unsigned char>(std::size_t(3) * k.width * k.height)};
  if (range) range->assign(std::size_t(k.width) * k.height, 0.0f);
  const int last = face_size_ - 1;
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    const Sample& s = samples_[i];
    if (s.face < 0) continue;
    const Image& face = faces[std::size_t(s.face)];
    const float u = std::clamp(s.u, 0.0f, float(last)), v = std::clamp(s.v, 0.0f, float(last));
    const int u0 = std::min(int(u), last - 1), v0 = std::min(int(v), last - 1);
    const float a = u - u0, b = v - v0;
    const std::size_t p00 = std::size_t(v0) * face_size_ + u0, p01 = p00 + 1,
                      p10 = p00 + face_size_, p11 = p10 + 1;
    const float w00 = (1 - a) * (1 - b), w01 = a * (1 - b), w10 = (1 - a) * b, w11 = a * b;
    for (int ch = 0; ch < 3; ++ch) {
      const float value = w00 * face.rgb[3 * p00 + ch] + w01 * face.rgb[3 * p01 + ch] +
                          w10 * face.rgb[3 * p10 + ch] + w11 * face.rgb[3 * p11 + ch];
      image.rgb[3 * i + ch] = static_cast<unsigned char>(std::lround(value));
    }
    if (range) {
      // Inverse depth is what varies linearly across a face's pixels on a plane; where a
      // neighbour saw nothing, the nearest pixel alone.
      const std::vector<float>& d = depths[std::size_t(s.face)];
      const float z00 = d[p00], z01 = d[p01], z10 = d[p10], z11 = d[p11];
      float z;
      if (z00 > 0 && z01 > 0 && z10 > 0 && z11 > 0) {
        z = 1.0f / (w00 / z00 + w01 / z01 + w10 / z10 + w11 / z11);
      } else {
        z = d[std::size_t(std::lround(v)) * face_size_ + std::size_t(std::lround(u))];
      }
      (*range)[i] = z * s.range_per_depth;
    }
  }
  return image;
}

}  // namespace isg::sim
