#include "sim/texture_overlay.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>
#include <random>
#include <string_view>

#include "common/untracked_allocations.hpp"
#include "sim/fast_random.hpp"
#include "sim/pinhole_frustum.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::sim {

namespace {

// The kind of surface a geom of the world shows, from its name and group
// (worlds/mjcf_generator.cpp names them); walls draw theirs from the seed.
SurfaceKind surfaceOf(const mjModel& model, int geom, Xoshiro256& rng) {
  if (model.geom_group[geom] == worlds::kCeilingGroup) return SurfaceKind::kCeiling;
  const char* raw = mj_id2name(&model, mjOBJ_GEOM, geom);
  const std::string_view name = raw ? raw : "";
  if (name.starts_with("floor")) return SurfaceKind::kFloor;
  if (name.starts_with("clutter")) return SurfaceKind::kMaterial;
  if (name.starts_with("door")) return SurfaceKind::kPaint;
  if (name.starts_with("column") || name.starts_with("stair")) return SurfaceKind::kConcrete;
  // Walls: cast concrete, plasterboard or painted, 4 : 3 : 3.
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  return u < 0.4   ? SurfaceKind::kConcrete
         : u < 0.7 ? SurfaceKind::kPlasterboard
                   : SurfaceKind::kPaint;
}

}  // namespace

TextureOverlay::TextureOverlay(const mjModel& model, std::uint64_t seed) : model_(model) {
  const auto textures = makeSurfaceTextures(seed);
  // Mesa keeps what it allocates for textures until exit (sim/renderer.cpp says why it is not
  // tracked under LeakSanitizer).
  const common::UntrackedAllocations untracked;
  glGenTextures(kSurfaceKinds, gl_textures_.data());
  for (int i = 0; i < kSurfaceKinds; ++i) {
    const SurfaceTexture& t = textures[std::size_t(i)];
    tile_metres_[std::size_t(i)] = t.metres;
    glBindTexture(GL_TEXTURE_2D, gl_textures_[std::size_t(i)]);
    glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, GL_TRUE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, t.size, t.size, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 t.rgb.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  setSurfaces(model, seed);
}

void TextureOverlay::setSurfaces(const mjModel& model, std::uint64_t seed) {
  Xoshiro256 rng(deriveSeed(seed, 0x7e48u, 0));
  std::uniform_real_distribution<double> offset(0.0, 10.0);
  kinds_.resize(std::size_t(model.ngeom));
  textured_.resize(std::size_t(model.ngeom));
  offsets_.resize(std::size_t(model.ngeom));
  for (int g = 0; g < model.ngeom; ++g) {
    const int group = model.geom_group[g];
    textured_[std::size_t(g)] = model.geom_type[g] == mjGEOM_BOX &&
                                (group == worlds::kBuildingGroup || group == worlds::kCeilingGroup);
    kinds_[std::size_t(g)] = surfaceOf(model, g, rng);
    offsets_[std::size_t(g)] = {offset(rng), offset(rng)};
  }
}

TextureOverlay::~TextureOverlay() {
  const common::UntrackedAllocations untracked;
  glDeleteTextures(kSurfaceKinds, gl_textures_.data());
}

void TextureOverlay::draw(const mjData& data, const Eigen::Isometry3d& B_T_C,
                          const bim::PinholeIntrinsics& k, double near, double far) const {
  glPushAttrib(GL_ALL_ATTRIB_BITS);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glLoadIdentity();
  // The frustum Renderer::camera gives MuJoCo, so the quads land on MuJoCo's pixels.
  const PinholeFrustum f = PinholeFrustum::of(k, near, far);
  glFrustum(f.centre - f.half_width, f.centre + f.half_width, f.bottom, f.top, f.near, f.far);
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  // B to OpenGL's eye frame (x right, y up, looking along −z): the optical frame with y and z
  // turned over.
  Eigen::Matrix4d eye_T_B = B_T_C.inverse().matrix();
  eye_T_B.row(1) *= -1.0;
  eye_T_B.row(2) *= -1.0;
  glLoadMatrixd(eye_T_B.data());  // column-major, as Eigen stores it
  glViewport(0, 0, k.width, k.height);
  glDisable(GL_LIGHTING);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  // Pulled towards the eye by a depth-slope term and a few units, so a face wins the test
  // against itself as MuJoCo wrote it, not against what lies in front.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -4.0f);
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);  // multiply the shaded colour by the texture
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  for (int kind = 0; kind < kSurfaceKinds; ++kind) {
    glBindTexture(GL_TEXTURE_2D, gl_textures_[std::size_t(kind)]);
    const double scale = 1.0 / tile_metres_[std::size_t(kind)];
    glBegin(GL_QUADS);
    for (int g = 0; g < model_.ngeom; ++g) {
      if (!textured_[std::size_t(g)] || int(kinds_[std::size_t(g)]) != kind) continue;
      const Eigen::Map<const Eigen::Vector3d> centre_B(data.geom_xpos + 3 * g);
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> axes(data.geom_xmat +
                                                                                9 * g);
      const Eigen::Map<const Eigen::Vector3d> half(model_.geom_size + 3 * g);
      const Eigen::Vector2d& offset = offsets_[std::size_t(g)];
      for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
          const int a = (axis + 1) % 3, b = (axis + 2) % 3;
          const Eigen::Vector3d face = centre_B + side * half[axis] * axes.col(axis);
          const Eigen::Vector3d ea = half[a] * axes.col(a), eb = half[b] * axes.col(b);
          const Eigen::Vector3d normal = axes.col(axis);
          // Texture axes in B: on a vertical face, along it horizontally and up; on a floor or
          // ceiling, x and y of B.
          Eigen::Vector3d s_axis, t_axis;
          if (std::abs(normal.z()) > 0.7) {
            s_axis = Eigen::Vector3d::UnitX();
            t_axis = Eigen::Vector3d::UnitY();
          } else {
            s_axis = Eigen::Vector3d::UnitZ().cross(normal).normalized();
            t_axis = Eigen::Vector3d::UnitZ();
          }
          for (const auto& [da, db] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
            const Eigen::Vector3d p = face + da * ea + db * eb;
            glTexCoord2d((p.dot(s_axis) + offset.x()) * scale,
                         (p.dot(t_axis) + offset.y()) * scale);
            glVertex3d(p.x(), p.y(), p.z());
          }
        }
      }
    }
    glEnd();
  }
  glMatrixMode(GL_MODELVIEW);
  glPopMatrix();
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glPopAttrib();
}

}  // namespace isg::sim
