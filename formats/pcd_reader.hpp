#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::formats {

// The largest PCD file a dataset may hold (far above a VLP-16 turn of ~30 000 points).
inline constexpr std::uintmax_t kMaxPcdBytes = 256u << 20;
// The most a binary_compressed file may unpack to.
inline constexpr std::size_t kMaxCompressedBytes = 1u << 30;

// Reads the points of a PCD file (v0.7, DATA ascii, binary or binary_compressed) into LiDAR points:
// fields x, y, z and time are required, intensity and ring optional, each found by name, of any of
// the PCD number types (F 4/8, U and I 1/2/4/8) with COUNT 1. Points with a non-finite x, y, z or
// time (a driver's "no return") are dropped. Anything else — a truncated file, an unknown field
// type, too few data bytes — is an InputError naming the file and the header line or point. Our own
// reader rather than PCL's: PCL crashes on some damaged files (an empty one, a garbage header), and
// a replay must never crash on a bad file.
std::vector<sensors::ScanPoint> readPcd(const std::string& path);
std::vector<sensors::ScanPoint> parsePcd(std::string_view bytes, const std::string& file);

// Every field of a PCD file (each of COUNT 1) as a column of numbers, for clouds whose fields are
// not ours (a driver's decoded cloud in the tests, say); the same checks and errors as readPcd.
struct PcdColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // values[field][point]

  // The column of a field; std::out_of_range when the file has no such field.
  const std::vector<double>& operator[](std::string_view name) const;
};
PcdColumns readPcdColumns(const std::string& path);
PcdColumns parsePcdColumns(std::string_view bytes, const std::string& file);

}  // namespace isg::formats
