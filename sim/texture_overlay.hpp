#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "bim/camera_models.hpp"
#include "sim/surface_textures.hpp"

namespace isg::sim {

// The building's surfaces textured for a camera. MuJoCo 2.2.2 maps a 2D texture on a box by the
// box's own x and y, so a wall's faces would show stripes; instead, after MuJoCo has drawn the
// scene, each box face of the building is drawn again as a quad whose texture coordinates run
// in metres along the face (world-anchored, so neighbouring faces agree), multiplied into the
// colour MuJoCo shaded, with the depth test passing only where that face is what is seen, and
// the depth buffer left as MuJoCo wrote it. Needs the GL context current (a Renderer's).
class TextureOverlay {
 public:
  TextureOverlay(const mjModel& model, std::uint64_t seed);
  ~TextureOverlay();
  TextureOverlay(const TextureOverlay&) = delete;
  TextureOverlay& operator=(const TextureOverlay&) = delete;

  // Draws over what is in the bound framebuffer, seen by the pinhole camera at B_T_C with the
  // frustum [near, far]; `data` gives where the geoms are.
  void draw(const mjData& data, const Eigen::Isometry3d& B_T_C, const bim::PinholeIntrinsics& k,
            double near, double far) const;

  // The kind of surface each geom shows (for the tests: what a wall or a floor gets).
  SurfaceKind kindOf(int geom) const { return kinds_[std::size_t(geom)]; }
  bool textured(int geom) const { return textured_[std::size_t(geom)]; }

 private:
  // Each geom's surface kind (walls drawn from the seed), whether it is textured, its offset.
  void setSurfaces(const mjModel& model, std::uint64_t seed);

  const mjModel& model_;
  std::array<unsigned int, kSurfaceKinds> gl_textures_{};
  std::array<double, kSurfaceKinds> tile_metres_{};
  std::vector<SurfaceKind> kinds_;
  std::vector<char> textured_;
  std::vector<Eigen::Vector2d> offsets_;  // each geom's texture offset, metres
};

}  // namespace isg::sim
