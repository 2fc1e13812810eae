#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace isg::formats {

// A VLP-16 data packet as the sensor sends it in one UDP datagram (port 2368): 12 blocks of
// 100 bytes (flag 0xFFEE, azimuth in 0.01°, 2 firing sequences × 16 lasers of a 2-mm distance
// and a 1-byte calibrated reflectivity), the time in µs past the hour and two factory bytes
// (return mode, product). docs/sensors.md describes the layout and the decoder's conventions.
inline constexpr std::size_t kVlp16PacketBytes = 1206;
inline constexpr int kVlp16Blocks = 12;
inline constexpr double kVlp16DistanceUnit = 0.002;  // m per distance count

enum class Vlp16ReturnMode : std::uint8_t { kStrongest = 0x37, kLast = 0x38, kDual = 0x39 };

// Which echo of its laser shot a point is. In dual-return mode a shot gives its last and its
// strongest echo; when they are the same echo (or the other block holds none) it is `kIdentical`,
// otherwise each is the near or the far one and the strong or the weak one.
enum class Vlp16Echo : std::uint8_t {
  kStrongest,  // single-return modes
  kLast,
  kIdentical,  // dual-return modes
  kNearStrongest,
  kNearWeak,
  kFarStrongest,
  kFarWeak,
};

// Which decoder's conventions a packet is decoded with: how a firing's azimuth is interpolated
// between the packet's block azimuths, and which table of firing times dual mode uses.
enum class Vlp16Convention : std::uint8_t {
  // Each firing sequence turns at the rate of its own block to the next one of another sequence
  // (in dual mode the next pair); the packet's last sequences continue the previous step. Both
  // blocks of a dual pair get the same azimuths, as they are one laser shot.
  kPerSequence,
  // tier4/nebula's VLP-16 decoder (ROS 2), to compare with its output: the second block of a dual
  // pair takes the next pair's azimuth, the last pair's first block is not interpolated, and the
  // firing times follow the single-return table whatever the mode.
  kNebula,
};

struct Vlp16DecodeOptions {
  // A return nearer than this or farther than max_range is dropped, as the drivers do (the ROS
  // driver's default minimum is 0.4 m; nebula's tests use 0.3 m and 300 m).
  double min_range = 0.4;
  double max_range = 130.0;
  Vlp16Convention convention = Vlp16Convention::kPerSequence;
};

// One decoded return, in the sensor's frame as the ROS drivers give it (x forward, y left, z up).
struct Vlp16Point {
  float x = 0, y = 0, z = 0;
  float distance = 0;         // m
  std::uint16_t azimuth = 0;  // 0.01° units in [0, 36000), clockwise from x seen from above
  std::uint8_t intensity = 0;
  std::uint8_t laser = 0;  // firing order
  std::uint8_t ring = 0;   // by elevation, 0 = −15°
  Vlp16Echo echo = Vlp16Echo::kStrongest;
  double time = 0.0;  // s: the packet's stamp plus the firing's offset in the packet
};

// The fixed fields of a packet.
struct Vlp16PacketHeader {
  Vlp16ReturnMode mode = Vlp16ReturnMode::kStrongest;
  std::uint8_t product = 0x22;                         // 0x22 = VLP-16
  std::uint32_t usec_past_hour = 0;                    // the sensor's own clock
  std::array<std::uint16_t, kVlp16Blocks> azimuths{};  // 0.01° units
};

// Laser shots and shots with at least one echo, per ring: the return statistics' raw counts.
struct Vlp16ShotTally {
  std::array<std::uint64_t, 16> shots{};
  std::array<std::uint64_t, 16> echoed{};
};

// Checks a packet's size, block flags, azimuths and return mode; throws common::InputError naming
// `file` and `where` (such as "packet 12") on a malformed one.
Vlp16PacketHeader readVlp16Header(std::span<const std::uint8_t> packet, const std::string& file,
                                  const std::string& where);

// Appends the packet's returns within range to `points`, in the packet's order (block, sequence,
// laser), stamped `stamp` + firing offset; counts its shots in `tally` when given. Returns the
// packet's header (checked as readVlp16Header does).
Vlp16PacketHeader decodeVlp16Packet(std::span<const std::uint8_t> packet, double stamp,
                                    const Vlp16DecodeOptions& options, const std::string& file,
                                    const std::string& where, std::vector<Vlp16Point>& points,
                                    Vlp16ShotTally* tally = nullptr);

}  // namespace isg::formats
