#include "sim/renderer.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <png.h>
#include <numbers>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/angles.hpp"
#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/untracked_allocations.hpp"
#include "sim/odometry_model.hpp"
#include "sim/pinhole_frustum.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::sim {

namespace {

// Mesa's EGL and GL drivers keep their set-up until exit (bim/untracked_allocations.hpp): what
// is allocated while EGL and the GL context are set up and torn down (MuJoCo's own context with
// them) is not tracked under LeakSanitizer, and nothing else is exempted.
using UntrackedMesaAllocations = common::UntrackedAllocations;

// A bar from `from` to `to` (B) drawn over the scene, when it has room for one more geom.
void addBar(mjvScene& scene, const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius,
            const float rgba[4]) {
  if (scene.ngeom >= scene.maxgeom) return;
  mjvGeom& g = scene.geoms[scene.ngeom++];
  const mjtNum size3[3] = {0, 0, 0};
  mjv_initGeom(&g, mjGEOM_CAPSULE, size3, nullptr, nullptr, rgba);
  mjv_makeConnector(&g, mjGEOM_CAPSULE, radius, from.x(), from.y(), from.z(), to.x(), to.y(),
                    to.z());
  g.category = mjCAT_DECOR;
}

// The picture's header, text, rows and end, written to whatever output `png` was given.
void encodePng(png_structp png, png_infop info, const Image& image) {
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The mark that lets isg render replace this picture, and nothing else (sensors/output_path.hpp).
  png_text software{};
  software.compression = PNG_TEXT_COMPRESSION_NONE;
  software.key = const_cast<char*>("Software");
  software.text = const_cast<char*>(common::kWrittenByIsg);
  png_set_text(png, info, &software, 1);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, const_cast<png_bytep>(image.rgb.data() + std::size_t(3) * image.width * y));
  }
  png_write_end(png, nullptr);
}

// Both of MuJoCo's eyes (one is used without stereo) at `eye`, looking along `forward` with
// `up`, through `frustum`.
void setGlCameras(mjvScene& scene, const Eigen::Vector3d& eye, const Eigen::Vector3d& forward,
                  const Eigen::Vector3d& up, const PinholeFrustum& frustum) {
  for (mjvGLCamera& c : scene.camera) {
    for (int i = 0; i < 3; ++i) {
      c.pos[i] = float(eye[i]);
      c.forward[i] = float(forward[i]);
      c.up[i] = float(up[i]);
    }
    c.frustum_near = float(frustum.near);
    c.frustum_far = float(frustum.far);
    c.frustum_center = float(frustum.centre);
    c.frustum_top = float(frustum.top);
    c.frustum_bottom = float(frustum.bottom);
  }
}

// The option's geom and site groups as they were, put back however the render ends (a throw
// from MuJoCo's or the overlay's drawing included): the next picture shows what it showed.
class GroupsRestored {
 public:
  explicit GroupsRestored(mjvOption& option) : option_(option) {
    std::copy_n(option.geomgroup, mjNGROUP, geom_groups_.begin());
    std::copy_n(option.sitegroup, mjNGROUP, site_groups_.begin());
  }
  ~GroupsRestored() {
    std::copy(geom_groups_.begin(), geom_groups_.end(), option_.geomgroup);
    std::copy(site_groups_.begin(), site_groups_.end(), option_.sitegroup);
  }
  GroupsRestored(const GroupsRestored&) = delete;
  GroupsRestored& operator=(const GroupsRestored&) = delete;

 private:
  mjvOption& option_;
  std::array<mjtByte, mjNGROUP> geom_groups_;
  std::array<mjtByte, mjNGROUP> site_groups_;
};

}  // namespace

struct Renderer::Egl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  Egl() {
    const UntrackedMesaAllocations untracked;
    // No display and no GPU here: Mesa's surfaceless platform gives a context without either.
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) fail("eglGetPlatformDisplayEXT is not available");
    display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY)
      fail("no surfaceless EGL display (is Mesa's libegl-mesa0 installed?)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) fail("eglInitialize failed");
    const EGLint attributes[] = {EGL_RED_SIZE,
                                 8,
                                 EGL_GREEN_SIZE,
                                 8,
                                 EGL_BLUE_SIZE,
                                 8,
                                 EGL_DEPTH_SIZE,
                                 24,
                                 EGL_RENDERABLE_TYPE,
                                 EGL_OPENGL_BIT,
                                 EGL_SURFACE_TYPE,
                                 EGL_PBUFFER_BIT,
                                 EGL_NONE};
    EGLConfig config;
    EGLint count = 0;
    if (!eglChooseConfig(display, attributes, &config, 1, &count) || count < 1) {
      fail("no EGL config with 8-bit RGB, a depth buffer and desktop OpenGL");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT) fail("eglCreateContext failed");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      fail("eglMakeCurrent without a surface failed (EGL_KHR_surfaceless_context missing?)");
    }
  }
  ~Egl() {
    const UntrackedMesaAllocations untracked;
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      eglTerminate(display);
    }
  }
  [[noreturn]] void fail(const std::string& what) {
    char code[32];
    std::snprintf(code, sizeof code, " (EGL error 0x%x)", eglGetError());
    throw std::runtime_error("headless rendering: " + what + code);
  }
};

Renderer::Renderer(const mjModel& model, int width, int height, Sampling sampling)
    : egl_(std::make_unique<Egl>()),
      model_(model),
      width_(width),
      height_(height),
      sampling_(sampling) {
  if (width > model.vis.global.offwidth || height > model.vis.global.offheight) {
    throw std::runtime_error("picture larger than the world's offscreen buffer (" +
                             std::to_string(model.vis.global.offwidth) + "x" +
                             std::to_string(model.vis.global.offheight) + ")");
  }
  const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  gl_renderer_ = name ? name : "unknown";
  mjv_defaultScene(&scene_);
  mjv_makeScene(&model, &scene_, 4000);
  {
    // Mesa's GL driver sets itself up on the first context (see UntrackedMesaAllocations).
    const UntrackedMesaAllocations untracked;
    mjr_defaultContext(&context_);
    // mjr_makeContext reads the samples per pixel from the model's visual options: a copy of
    // the model's struct (its arrays shared, only read) says one sample where pixels are sampled
    // at their centres.
    mjModel sampled = model;
    if (sampling == Sampling::kPixelCentres) sampled.vis.quality.offsamples = 0;
    mjr_makeContext(&sampled, &context_, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  }
  mjv_defaultOption(&option_);
  option_.geomgroup[worlds::kRobotGroup] = 1;
}

void Renderer::enableSurfaceTextures(std::uint64_t seed) {
  overlay_ = std::make_unique<TextureOverlay>(model_, seed);
}

Renderer::~Renderer() {
  overlay_.reset();  // its GL textures go while the context is there
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

Image Renderer::render(mjData& data, mjvCamera& camera, bool ceilings,
                       const std::function<void(mjvScene&)>& adjust, std::vector<float>* depth,
                       const std::function<void()>& after_draw) {
  option_.geomgroup[worlds::kCeilingGroup] = ceilings;
  mjv_updateScene(&model_, &data, &option_, nullptr, &camera, mjCAT_ALL, &scene_);
  if (adjust) adjust(scene_);
  const mjrRect viewport = {0, 0, width_, height_};
  mjr_render(viewport, &scene_, &context_);
  if (after_draw) {
    mjr_setBuffer(mjFB_OFFSCREEN, &context_);
    after_draw();
  }
  Image image{width_, height_, std::vector<unsigned char>(std::size_t(3) * width_ * height_)};
  std::vector<unsigned char> flipped(image.rgb.size());
  std::vector<float> depth_flipped(depth ? std::size_t(width_) * height_ : 0);
  mjr_readPixels(flipped.data(), depth ? depth_flipped.data() : nullptr, viewport, &context_);
  // OpenGL's rows start at the bottom; pictures start at the top.
  for (int y = 0; y < height_; ++y) {
    std::copy_n(flipped.begin() + std::size_t(3) * width_ * (height_ - 1 - y), 3 * width_,
                image.rgb.begin() + std::size_t(3) * width_ * y);
  }
  if (depth) {
    depth->resize(depth_flipped.size());
    for (int y = 0; y < height_; ++y) {
      std::copy_n(depth_flipped.begin() + std::size_t(width_) * (height_ - 1 - y), width_,
                  depth->begin() + std::size_t(width_) * y);
    }
  }
  return image;
}

Image Renderer::topDown(mjData& data) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FIXED;
  camera.fixedcamid = mj_name2id(&model_, mjOBJ_CAMERA, "top");
  return render(data, camera, false);
}

Image Renderer::chase(mjData& data, const Eigen::Isometry3d& B_T_R) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FREE;
  const Eigen::Vector3d p = B_T_R.translation();
  camera.lookat[0] = p.x();
  camera.lookat[1] = p.y();
  camera.lookat[2] = p.z();
  camera.distance = 3.2;
  camera.elevation = -32.0;
  // MuJoCo's free camera looks along its azimuth: from behind the robot is its own heading.
  camera.azimuth = common::yawOf(B_T_R.linear()) * 180.0 / std::numbers::pi;
  return render(data, camera, false);
}

Image Renderer::planView(mjData& data, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                         const std::vector<Eigen::Vector3d>& route) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FREE;
  return render(data, camera, false, [&](mjvScene& scene) {
    // MuJoCo 2.2.2 renders in perspective only. A camera 1 km above the building with a field of
    // view just wide enough is orthographic to the eye: a 3 m wall's top and foot differ by 0.3 %
    // of their distance, well under a pixel, so walls are seen as their footprints and door
    // openings as gaps.
    constexpr double kDistance = 1000.0;
    const Eigen::Vector2d centre = 0.5 * (lo + hi);
    const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1.0)) * 1.06;
    const double aspect = double(width_) / double(height_);
    const double half_height = 0.5 * std::max(size.y(), size.x() / aspect);
    for (int eye = 0; eye < 2; ++eye) {
      mjvGLCamera& c = scene.camera[eye];
      c.pos[0] = float(centre.x());
      c.pos[1] = float(centre.y());
      c.pos[2] = float(kDistance);
      c.forward[0] = 0.0f;
      c.forward[1] = 0.0f;
      c.forward[2] = -1.0f;
      c.up[0] = 0.0f;
      c.up[1] = 1.0f;
      c.up[2] = 0.0f;
      c.frustum_near = float(kDistance - 100.0);
      c.frustum_far = float(kDistance + 100.0);
      c.frustum_center = 0.0f;
      c.frustum_top = float(half_height * c.frustum_near / kDistance);
      c.frustum_bottom = -c.frustum_top;
    }
    // A plan is a cut below the lintels: the wall above each door (worlds/mjcf_generator.hpp
    // names it wall/<wall>/lintel/<door>) is left out, so the opening shows.
    int kept = 0;
    for (int i = 0; i < scene.ngeom; ++i) {
      const mjvGeom& g = scene.geoms[i];
      const char* name =
          g.objtype == mjOBJ_GEOM ? mj_id2name(&model_, mjOBJ_GEOM, g.objid) : nullptr;
      if (name != nullptr && std::strstr(name, "/lintel/") != nullptr) continue;
      scene.geoms[kept++] = g;
    }
    scene.ngeom = kept;
    // The route as a red line just above the floor.
    const float red[4] = {0.85f, 0.1f, 0.1f, 1.0f};
    for (std::size_t i = 1; i < route.size(); ++i) {
      addBar(scene, route[i - 1], route[i], std::max(0.02, 0.004 * size.x()), red);
    }
  });
}

Image Renderer::lookAt(mjData& data, const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                       double vertical_fov_deg, const std::vector<Line>& lines) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FREE;
  return render(data, camera, false, [&](mjvScene& scene) {
    const Eigen::Vector3d forward = (target - eye).normalized();
    Eigen::Vector3d up = forward.cross(Eigen::Vector3d::UnitZ()).cross(forward);
    up = up.norm() < 1e-9 ? Eigen::Vector3d::UnitY() : up.normalized();
    PinholeFrustum frustum;
    frustum.near = 0.05;
    frustum.far = 500.0;
    frustum.top = frustum.near * std::tan(0.5 * vertical_fov_deg * std::numbers::pi / 180.0);
    frustum.bottom = -frustum.top;
    setGlCameras(scene, eye, forward, up, frustum);
    const float red[4] = {0.9f, 0.1f, 0.1f, 1.0f};
    for (const Line& line : lines) addBar(scene, line.from, line.to, 0.025, red);
  });
}

Image Renderer::camera(mjData& data, const Eigen::Isometry3d& B_T_C,
                       const bim::PinholeIntrinsics& k, double far_m, std::vector<float>* depth) {
  if (sampling_ != Sampling::kPixelCentres) {
    throw std::logic_error("Renderer::camera needs a renderer that samples pixel centres");
  }
  if (k.width != width_ || k.height != height_) {
    throw std::logic_error("Renderer::camera: the renderer is " + std::to_string(width_) + "x" +
                           std::to_string(height_) + ", the camera " + std::to_string(k.width) +
                           "x" + std::to_string(k.height));
  }
  // Near enough for a camera against a wall, far enough from 0 that the 24-bit depth buffer
  // resolves 10 m to a tenth of a millimetre (its step is about z² / near × 2⁻²⁴).
  constexpr double kNear = 0.05;
  mjvCamera free_camera;
  mjv_defaultCamera(&free_camera);
  free_camera.type = mjCAMERA_FREE;
  const GroupsRestored restored(option_);
  option_.geomgroup[worlds::kRobotGroup] = 0;
  // Sites (the rooms' markers) are for people's pictures; a camera sees the building.
  std::fill_n(option_.sitegroup, mjNGROUP, mjtByte(0));
  Image image = render(
      data, free_camera, true,
      [&](mjvScene& scene) {
        // The optical frame's axes in B: forward is its z, up is its −y.
        const Eigen::Vector3d eye = B_T_C.translation();
        const Eigen::Vector3d forward = B_T_C.linear().col(2);
        const Eigen::Vector3d up = -B_T_C.linear().col(1);
        // Ceilings are see-through in pictures from above (the world's ceiling material); to a
        // camera inside the building they are solid, and drawn into the depth buffer.
        for (int i = 0; i < scene.ngeom; ++i) {
          mjvGeom& g = scene.geoms[i];
          if (g.objtype == mjOBJ_GEOM && model_.geom_group[g.objid] == worlds::kCeilingGroup) {
            g.rgba[3] = 1.0f;
            g.transparent = 0;
          }
        }
        setGlCameras(scene, eye, forward, up, PinholeFrustum::of(k, kNear, far_m));
      },
      depth,
      overlay_ ? std::function<void()>([&] { overlay_->draw(data, B_T_C, k, kNear, far_m); })
               : std::function<void()>());
  if (depth) {
    // The buffer's d in [0, 1] back to the distance along the axis: OpenGL's perspective maps
    // z in [near, far] to d = (1/near − 1/z) / (1/near − 1/far).
    const double a = 1.0 / kNear, b = 1.0 / kNear - 1.0 / far_m;
    for (float& d : *depth) d = d >= 1.0f ? 0.0f : float(1.0 / (a - double(d) * b));
  }
  return image;
}

void writePng(const std::string& path, const Image& image) {
  // Written beside its place and renamed into it: a reader never sees half a picture.
  common::AtomicFile atomic(path, common::OutputKind::kPng, true);
  FILE* file = std::fopen(atomic.temporary().c_str(), "wb");
  if (file == nullptr) {
    throw common::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    throw common::InputError(path, "", "cannot write PNG");
  }
  png_init_io(png, file);
  encodePng(png, info, image);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(file) != 0) {
    throw common::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
  }
  atomic.commit();
}

std::string pngBytes(const Image& image) {
  std::string bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("cannot encode a PNG picture");
  }
  png_set_write_fn(
      png, &bytes,
      [](png_structp p, png_bytep data, png_size_t length) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(data), length);
      },
      nullptr);
  encodePng(png, info, image);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

}  // namespace isg::sim
