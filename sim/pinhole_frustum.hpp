#pragma once

#include "bim/camera_models.hpp"

namespace isg::sim {

// The OpenGL frustum of a pinhole camera through the image's outer pixel edges (u = −½ …
// width − ½, v = −½ … height − ½), at the near plane: what MuJoCo's camera is given and what the
// texture overlay draws with, so that both land on the same pixels. MuJoCo makes the frustum's
// half-width from the viewport's aspect and its height, which holds for square pixels; the
// centre moves when the principal point is off the image's centre.
struct PinholeFrustum {
  double near = 0.0, far = 0.0;
  double top = 0.0, bottom = 0.0;  // at the near plane, up positive
  double centre = 0.0;             // horizontal offset of the frustum's centre
  double half_width = 0.0;

  static PinholeFrustum of(const bim::PinholeIntrinsics& k, double near, double far) {
    PinholeFrustum f;
    f.near = near;
    f.far = far;
    f.top = (k.cy + 0.5) / k.fy * near;
    f.bottom = -(k.height - 0.5 - k.cy) / k.fy * near;
    f.centre = (k.width - 1.0 - 2.0 * k.cx) / (2.0 * k.fx) * near;
    f.half_width = 0.5 * double(k.width) / k.height * (f.top - f.bottom);
    return f;
  }
};

}  // namespace isg::sim
