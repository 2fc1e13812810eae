#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::sensors {

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

}  // namespace isg::sensors
