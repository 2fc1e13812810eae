#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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
  // Throws std::runtime_error with the EGL step that failed when no context can be made.
  Renderer(const mjModel& model, int width, int height);
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

  const std::string& glRenderer() const { return gl_renderer_; }

 private:
  // `adjust` changes the scene between MuJoCo's update and the drawing (cameras, extra geoms).
  Image render(mjData& data, mjvCamera& camera, bool ceilings,
               const std::function<void(mjvScene&)>& adjust = nullptr);

  struct Egl;
  std::unique_ptr<Egl> egl_;
  const mjModel& model_;
  int width_, height_;
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
