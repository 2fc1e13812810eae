#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace isg::sim {

// What a building's surfaces look like to a camera: seamless tiles of texture, drawn from the
// run's seed, that a feature detector finds corners on (docs/sensors.md, "Surfaces").
enum class SurfaceKind {
  kConcrete,      // cast walls and columns: grey, mottled, formwork joints, tie holes, stains
  kPlasterboard,  // partitions: off-white, taped seams every 1.2 m, screw heads, pencil marks
  kPaint,         // painted walls: a colour of the seed's, roller mottle, scuffs
  kFloor,         // the slab: darker concrete with painted layout lines and spots
  kCeiling,       // suspended ceiling: 0.6 m tiles on a dark grid, speckled
  kMaterial,      // clutter: timber pallets and stacked boards
};
inline constexpr int kSurfaceKinds = 6;

struct SurfaceTexture {
  SurfaceKind kind = SurfaceKind::kConcrete;
  int size = 0;         // pixels on a side (square)
  double metres = 0.0;  // metres the tile spans on a side
  // RGB, row 0 first. A factor on the renderer's shaded colour (255 keeps it): the lighting
  // stays MuJoCo's, the texture adds the detail.
  std::vector<unsigned char> rgb;
};

// One tile of every kind, from `seed`: the same seed, the same tiles.
std::array<SurfaceTexture, kSurfaceKinds> makeSurfaceTextures(std::uint64_t seed, int size = 512);

}  // namespace isg::sim
