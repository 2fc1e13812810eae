// libFuzzer harness: bytes → the import's geometry (ifc/mesh_fit.hpp) on arbitrary faces: fitWall,
// extentAlong along the fitted axis and footprintOf. The IFC import's own harness
// (ifc_import_fuzzer) runs IFC++ in a child process, out of libFuzzer's sight; this one reaches
// the fitting code directly. No input may crash, hang or trip a sanitizer.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "ifc/mesh_fit.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Each face: one byte for its vertex count (3-10), then that many points of three 16-bit
  // coordinates in millimetres (±32 m), so that every input is a mesh.
  isg::ifc::Mesh mesh;
  std::size_t at = 0;
  while (at < size && mesh.size() < 256) {
    const int count = 3 + data[at++] % 8;
    isg::ifc::Face face;
    for (int i = 0; i < count && at + 6 <= size; ++i) {
      std::int16_t c[3];
      std::memcpy(c, data + at, sizeof c);
      at += sizeof c;
      face.emplace_back(c[0] / 1000.0, c[1] / 1000.0, c[2] / 1000.0);
    }
    if (face.size() >= 3) mesh.push_back(face);
  }
  if (const auto fit = isg::ifc::fitWall(mesh, Eigen::Vector2d(1.0, 0.0))) {
    isg::ifc::extentAlong(mesh, fit->start, fit->end);
  }
  isg::ifc::footprintOf(mesh);
  isg::ifc::boundsOf(mesh);
  return 0;
}
