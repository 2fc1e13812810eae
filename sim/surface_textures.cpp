#include "sim/surface_textures.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "sim/fast_random.hpp"

namespace isg::sim {

namespace {

// A greyscale field on the tile, values around 1, wrapping at the tile's edges.
class Field {
 public:
  explicit Field(int size) : size_(size), v_(std::size_t(size) * size, 1.0) {}
  double& at(int x, int y) {
    x = ((x % size_) + size_) % size_;
    y = ((y % size_) + size_) % size_;
    return v_[std::size_t(y) * size_ + x];
  }
  int size() const { return size_; }

  // Value noise: a random lattice of `cells` per side, bilinearly blended, added with amplitude.
  void addNoise(Xoshiro256& rng, int cells, double amplitude) {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<double> lattice(std::size_t(cells) * cells);
    for (double& l : lattice) l = uniform(rng);
    auto node = [&](int i, int j) {
      return lattice[std::size_t((j + cells) % cells) * cells + (i + cells) % cells];
    };
    for (int y = 0; y < size_; ++y) {
      const double fy = double(y) * cells / size_;
      const int j = int(fy);
      const double ty = fy - j, sy = ty * ty * (3 - 2 * ty);
      for (int x = 0; x < size_; ++x) {
        const double fx = double(x) * cells / size_;
        const int i = int(fx);
        const double tx = fx - i, sx = tx * tx * (3 - 2 * tx);
        const double top = node(i, j) * (1 - sx) + node(i + 1, j) * sx;
        const double bottom = node(i, j + 1) * (1 - sx) + node(i + 1, j + 1) * sx;
        at(x, y) += amplitude * (top * (1 - sy) + bottom * sy);
      }
    }
  }
  // A filled disc of `radius` pixels, multiplied by `factor`.
  void disc(double cx, double cy, double radius, double factor) {
    const int r = int(std::ceil(radius));
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (dx * dx + dy * dy <= radius * radius) at(int(cx) + dx, int(cy) + dy) *= factor;
      }
    }
  }
  // A line `width` pixels wide from (x0, y0) to (x1, y1), multiplied by `factor`.
  void line(double x0, double y0, double x1, double y1, double width, double factor) {
    const double length = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, int(length * 2));
    // Each pixel the line covers is multiplied once, however many of its steps cover it.
    std::vector<char> marked(std::size_t(size_) * size_, 0);
    for (int k = 0; k <= steps; ++k) {
      const double t = double(k) / steps;
      const double cx = x0 + t * (x1 - x0), cy = y0 + t * (y1 - y0);
      const int r = int(std::ceil(0.5 * width));
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          if (dx * dx + dy * dy > 0.25 * width * width + 0.25) continue;
          const int x = ((int(cx) + dx) % size_ + size_) % size_;
          const int y = ((int(cy) + dy) % size_ + size_) % size_;
          char& m = marked[std::size_t(y) * size_ + x];
          if (!m) at(x, y) *= factor;
          m = 1;
        }
      }
    }
  }

  // The field times `colour` (0–1 each) as 8-bit RGB.
  std::vector<unsigned char> rgb(const std::array<double, 3>& colour) const {
    std::vector<unsigned char> out(v_.size() * 3);
    for (std::size_t i = 0; i < v_.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        out[3 * i + c] = static_cast<unsigned char>(
            std::clamp(std::lround(255.0 * colour[c] * v_[i]), 0L, 255L));
      }
    }
    return out;
  }

 private:
  int size_;
  std::vector<double> v_;
};

double draw(Xoshiro256& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Blotches: `count` soft dark or light discs of radius up to `radius` pixels.
void blotches(Field& f, Xoshiro256& rng, int count, double radius, double lo, double hi) {
  for (int i = 0; i < count; ++i) {
    f.disc(draw(rng, 0, f.size()), draw(rng, 0, f.size()), draw(rng, 0.3, 1.0) * radius,
           draw(rng, lo, hi));
  }
}

// Strokes: `count` straight marks anywhere on the tile, in any direction, their length (pixels),
// width (pixels) and darkening drawn from the ranges given.
void strokes(Field& f, Xoshiro256& rng, int count, std::pair<double, double> length,
             std::pair<double, double> width, std::pair<double, double> factor) {
  for (int i = 0; i < count; ++i) {
    const double x = draw(rng, 0, f.size()), y = draw(rng, 0, f.size());
    const double angle = draw(rng, 0, 6.2832), l = draw(rng, length.first, length.second);
    const double w = draw(rng, width.first, width.second);
    f.line(x, y, x + l * std::cos(angle), y + l * std::sin(angle), w,
           draw(rng, factor.first, factor.second));
  }
}

// Cast concrete on a 2.4 m tile: panels of 1.2 m × 2.4 m between formwork joints, tie holes on
// a 0.6 m grid, mottle and stains.
SurfaceTexture concrete(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kConcrete, size, 2.4, {}};
  Field f(size);
  f.addNoise(rng, 8, 0.06);
  f.addNoise(rng, 32, 0.05);
  f.addNoise(rng, 128, 0.05);
  const double px = size / t.metres;
  f.line(0, 0, 0, size, 2, 0.7);
  f.line(0.5 * size, 0, 0.5 * size, size, 2, 0.7);
  f.line(0, 0, size, 0, 2, 0.75);
  for (double x = 0.3; x < t.metres; x += 0.6) {
    for (double y = 0.3; y < t.metres; y += 0.6) f.disc(x * px, y * px, 0.012 * px, 0.35);
  }
  blotches(f, rng, 40, 0.08 * px, 0.8, 0.95);
  blotches(f, rng, 200, 0.01 * px, 0.6, 0.85);
  t.rgb = f.rgb({0.72, 0.71, 0.69});
  return t;
}

// Plasterboard on a 2.4 m tile: boards 1.2 m wide, taped joints, screw heads every 0.3 m on
// the studs 0.6 m apart, pencil marks.
SurfaceTexture plasterboard(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kPlasterboard, size, 2.4, {}};
  Field f(size);
  f.addNoise(rng, 64, 0.02);
  const double px = size / t.metres;
  for (double x : {0.0, 1.2}) f.line(x * px, 0, x * px, size, 0.05 * px, 0.93);
  for (double x = 0.0; x < t.metres; x += 0.6) {
    for (double y = 0.15; y < t.metres; y += 0.3) f.disc(x * px + 0.02 * px, y * px, 2.0, 0.55);
  }
  strokes(f, rng, 12, {0.05 * px, 0.25 * px}, {1.5, 1.5}, {0.5, 0.5});
  blotches(f, rng, 30, 0.03 * px, 0.85, 0.97);
  t.rgb = f.rgb({0.95, 0.94, 0.91});
  return t;
}

// Paint on a 2.4 m tile: a colour from the seed, roller mottle, scuffs and fixings.
SurfaceTexture paint(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kPaint, size, 2.4, {}};
  Field f(size);
  f.addNoise(rng, 16, 0.04);
  f.addNoise(rng, 96, 0.03);
  const double px = size / t.metres;
  strokes(f, rng, 25, {0.03 * px, 0.2 * px}, {1.5, 4.0}, {0.55, 0.8});
  blotches(f, rng, 60, 0.015 * px, 0.5, 0.8);
  const std::array<double, 3> colour = {draw(rng, 0.6, 0.95), draw(rng, 0.6, 0.95),
                                        draw(rng, 0.6, 0.95)};
  t.rgb = f.rgb(colour);
  return t;
}

// The floor slab on a 4.8 m tile: concrete, layout lines painted every 2.4 m, spots and marks.
SurfaceTexture floorSlab(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kFloor, size, 4.8, {}};
  Field f(size);
  f.addNoise(rng, 12, 0.07);
  f.addNoise(rng, 96, 0.05);
  const double px = size / t.metres;
  blotches(f, rng, 300, 0.015 * px, 0.55, 0.85);
  blotches(f, rng, 20, 0.2 * px, 0.85, 0.95);
  std::vector<unsigned char> rgb = f.rgb({0.62, 0.61, 0.6});
  // Layout lines in paint (yellow), drawn over the grey.
  Field lines(size);
  for (double x : {0.0, 2.4}) lines.line(x * px, 0, x * px, size, 0.05 * px, 0.0);
  lines.line(0, 1.2 * px, size, 1.2 * px, 0.05 * px, 0.0);
  for (std::size_t i = 0; i < rgb.size() / 3; ++i) {
    if (lines.at(int(i % size), int(i / size)) < 0.5) {
      rgb[3 * i] = 235;
      rgb[3 * i + 1] = 200;
      rgb[3 * i + 2] = 40;
    }
  }
  t.rgb = std::move(rgb);
  return t;
}

// A suspended ceiling on a 2.4 m tile: 0.6 m tiles, a dark grid, speckle.
SurfaceTexture ceiling(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kCeiling, size, 2.4, {}};
  Field f(size);
  f.addNoise(rng, 128, 0.06);
  const double px = size / t.metres;
  blotches(f, rng, 800, 2.0, 0.7, 0.9);
  for (double x = 0.0; x < t.metres; x += 0.6) {
    f.line(x * px, 0, x * px, size, 0.015 * px, 0.45);
    f.line(0, x * px, size, x * px, 0.015 * px, 0.45);
  }
  t.rgb = f.rgb({0.97, 0.97, 0.96});
  return t;
}

// Material on site on a 1.2 m tile: timber boards 0.1–0.15 m wide with gaps, grain and knots.
SurfaceTexture material(Xoshiro256& rng, int size) {
  SurfaceTexture t{SurfaceKind::kMaterial, size, 1.2, {}};
  Field f(size);
  f.addNoise(rng, 48, 0.08);
  const double px = size / t.metres;
  double y = 0.0;
  while (y < t.metres - 0.08) {
    f.line(0, y * px, size, y * px, 0.015 * px, 0.3);
    y += draw(rng, 0.1, 0.15);
  }
  f.line(0, y * px, size, y * px, 0.015 * px, 0.3);
  blotches(f, rng, 25, 0.012 * px, 0.4, 0.6);
  t.rgb = f.rgb({0.78, 0.62, 0.42});
  return t;
}

}  // namespace

std::array<SurfaceTexture, kSurfaceKinds> makeSurfaceTextures(std::uint64_t seed, int size) {
  // One generator per kind: changing one kind's drawing leaves the others as they were.
  auto rng = [&](int kind) { return Xoshiro256(deriveSeed(seed, 0x7e47u, std::uint64_t(kind))); };
  auto r0 = rng(0), r1 = rng(1), r2 = rng(2), r3 = rng(3), r4 = rng(4), r5 = rng(5);
  return {concrete(r0, size),  plasterboard(r1, size), paint(r2, size),
          floorSlab(r3, size), ceiling(r4, size),      material(r5, size)};
}

}  // namespace isg::sim
