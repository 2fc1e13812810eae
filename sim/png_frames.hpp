#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace isg::sim {

// Camera frames as PNG files, written fast (zlib's fastest level: a frame stream is written
// thousands of times and read once). Each throws common::InputError naming the path on failure.
void writeRgbFrame(const std::filesystem::path& path, int width, int height,
                   const std::vector<unsigned char>& rgb);
// 16-bit grey, as depth images are stored (EuRoC, RealSense): one value per pixel, row 0 at the
// top, written big-endian as PNG requires.
void writeGray16Frame(const std::filesystem::path& path, int width, int height,
                      const std::vector<std::uint16_t>& values);

}  // namespace isg::sim
