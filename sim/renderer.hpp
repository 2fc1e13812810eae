#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bim/camera_models.hpp"
#include "sim/texture_overlay.hpp"

namespace isg::sim {

// Pictures of a MuJoCo world without a display or a GPU: an OpenGL context from EGL on Mesa's
// surfaceless platform (software rendering), MuJoCo's own renderer into its offscreen buffer.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;  // row 0 at the top
};

class Renderer {
 public:
  // How a pixel is sampled. Pictures for people are smoothed (MuJoCo's 4 samples per pixel,
  // averaged); a camera's pixels are sampled once, at their centres: a multisampled depth buffer
  // is read back from its first sample, 1/8 pixel left of and 3/8 below the centre, which puts
  // depth 7 mm off on a floor seen 2.4 m away.
  enum class Sampling { kSmoothed, kPixelCentres };
  // Throws std::runtime_error with the EGL step that failed when no context can be made.
  Renderer(const mjModel& model, int width, int height, Sampling sampling = Sampling::kSmoothed);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The whole building from straight above (the world's "top" camera), ceilings hidden.
  Image topDown(mjData& data);
  // The building as a plan: straight down, orthographic to the eye (walls as footprints, door
  // openings as gaps), framing [lo, hi] of B, ceilings hidden, with `route` (points in B) drawn as
  // a red line.
  Image planView(mjData& data, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                 const std::vector<Eigen::Vector3d>& route);
  // Behind and above the robot at B_T_R, looking at it.
  Image chase(mjData& data, const Eigen::Isometry3d& B_T_R);
  // A perspective view from `eye` towards `target` (B) with a vertical field of view of
  // `vertical_fov_deg`, ceilings hidden, `lines` (pairs of points in B) drawn over it as red
  // bars: a BCF topic's snapshot with the element's outline.
  struct Line {
    Eigen::Vector3d from, to;
  };
  Image lookAt(mjData& data, const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
               double vertical_fov_deg, const std::vector<Line>& lines);

  // What a pinhole camera at B_T_C (its optical frame: z forward, x right, y down) sees, with
  // the ceilings and without the robot's body; the renderer's size must be the camera's and its
  // sampling kPixelCentres. When
  // `depth` is given it receives each pixel's depth, metres along the optical axis (row 0 at the
  // top), and 0 where nothing lies within `far_m`.
  Image camera(mjData& data, const Eigen::Isometry3d& B_T_C, const bim::PinholeIntrinsics& k,
               double far_m, std::vector<float>* depth);

  // From now on camera() draws the building's surfaces textured from `seed`
  // (sim/texture_overlay.hpp): what a feature tracker needs, and what a real site shows.
  void enableSurfaceTextures(std::uint64_t seed);

  const std::string& glRenderer() const { return gl_renderer_; }

 private:
  // `adjust` changes the scene between MuJoCo's update and the drawing (cameras, extra geoms).
  // `depth`, when given, receives the depth buffer's values in [0, 1], row 0 at the top;
  // `after_draw` draws over MuJoCo's picture before it is read.
  Image render(mjData& data, mjvCamera& camera, bool ceilings,
               const std::function<void(mjvScene&)>& adjust = nullptr,
               std::vector<float>* depth = nullptr,
               const std::function<void()>& after_draw = nullptr);

  struct Egl;
  std::unique_ptr<Egl> egl_;
  std::unique_ptr<TextureOverlay> overlay_;
  const mjModel& model_;
  int width_, height_;
  Sampling sampling_;
  mjvScene scene_;
  mjrContext context_;
  mjvOption option_;
  std::string gl_renderer_;
};

// Writes an 8-bit RGB PNG; throws std::runtime_error naming the path on failure.
void writePng(const std::string& path, const Image& image);
// The same PNG as bytes (a picture put into an archive).
std::string pngBytes(const Image& image);

}  // namespace isg::sim
