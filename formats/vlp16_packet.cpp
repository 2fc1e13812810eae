#include "formats/vlp16_packet.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/input_error.hpp"
#include "sensors/vlp16_layout.hpp"

namespace isg::formats {

namespace {

constexpr std::size_t kBlockBytes = 100;
constexpr std::size_t kTailOffset = kVlp16Blocks * kBlockBytes;  // timestamp, then mode, product
constexpr std::uint16_t kBlockFlag = 0xFFEE;                     // bytes FF EE, read big-endian
constexpr int kFullTurn = 36000;

std::uint16_t littleEndian16(const std::uint8_t* at) { return std::uint16_t(at[0] | at[1] << 8); }

std::string hex(unsigned value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%0*X", digits, value);
  return text;
}

// One firing's distance count and reflectivity in block `block`, sequence `sequence`.
struct RawEcho {
  std::uint16_t count;
  std::uint8_t reflectivity;
};

RawEcho echoAt(std::span<const std::uint8_t> packet, int block, int sequence, int laser) {
  const std::uint8_t* at = packet.data() + block * kBlockBytes + 4 +
                           3 * (sensors::Vlp16Layout::kLasers * sequence + laser);
  return {littleEndian16(at), at[2]};
}

// Azimuth of the block's first sequence and its step to the next sequence pair (0.01° units),
// under the chosen interpolation.
struct BlockTurn {
  double azimuth;
  double step;  // over two firing sequences
};

std::array<BlockTurn, kVlp16Blocks> blockTurns(const Vlp16PacketHeader& header, bool dual,
                                               Vlp16Convention interpolation) {
  const auto& az = header.azimuths;
  const int stride = dual ? 2 : 1;  // blocks per firing sequence pair
  auto forward = [](int from, int to) { return double((kFullTurn + to - from) % kFullTurn); };
  std::array<BlockTurn, kVlp16Blocks> turns{};
  if (interpolation == Vlp16Convention::kPerSequence) {
    for (int b = 0; b < kVlp16Blocks; ++b) {
      const int first = b - b % stride;  // the pair's first block
      const int next = first + stride;
      const double step = next < kVlp16Blocks ? forward(az[first], az[next])
                                              : forward(az[first - stride], az[first]);
      turns[b] = {double(az[first]), step};
    }
    return turns;
  }
  // nebula: a running "next azimuth" read `stride` blocks ahead of each block in turn.
  double last_step = 0.0;
  int next_azimuth = az[0];
  for (int b = 0; b < kVlp16Blocks; ++b) {
    const int azimuth = b == 0 ? az[0] : next_azimuth;
    double step;
    if (b < kVlp16Blocks - stride) {
      next_azimuth = az[b + stride];
      step = forward(azimuth, next_azimuth);
      last_step = step;
    } else {
      step = b == kVlp16Blocks - stride ? 0.0 : last_step;
    }
    turns[b] = {double(azimuth), step};
  }
  return turns;
}

Vlp16Echo classifyEcho(RawEcho own, RawEcho other, Vlp16ReturnMode mode) {
  if (mode == Vlp16ReturnMode::kStrongest) return Vlp16Echo::kStrongest;
  if (mode == Vlp16ReturnMode::kLast) return Vlp16Echo::kLast;
  if (other.count == 0 || other.count == own.count) return Vlp16Echo::kIdentical;
  const bool far = own.count > other.count;
  // The sensor puts the last echo in a pair's first block and the strongest of the others in
  // the second: with equal reflectivities the near one is the one it called strongest.
  const bool strong =
      own.reflectivity == other.reflectivity ? !far : own.reflectivity > other.reflectivity;
  if (far) return strong ? Vlp16Echo::kFarStrongest : Vlp16Echo::kFarWeak;
  return strong ? Vlp16Echo::kNearStrongest : Vlp16Echo::kNearWeak;
}

}  // namespace

Vlp16PacketHeader readVlp16Header(std::span<const std::uint8_t> packet, const std::string& file,
                                  const std::string& where) {
  auto fail = [&](const std::string& reason) {
    throw common::InputError(file, "", where + ": " + reason);
  };
  if (packet.size() != kVlp16PacketBytes) {
    fail("has " + std::to_string(packet.size()) + " bytes, a VLP-16 data packet has " +
         std::to_string(kVlp16PacketBytes));
  }
  Vlp16PacketHeader header;
  for (int b = 0; b < kVlp16Blocks; ++b) {
    const std::uint8_t* block = packet.data() + b * kBlockBytes;
    const std::uint16_t flag = std::uint16_t(block[0] << 8 | block[1]);
    if (flag != kBlockFlag) {
      fail("block " + std::to_string(b) + " starts " + hex(block[0], 2) + " " + hex(block[1], 2) +
           ", not FF EE (not a VLP-16 data packet)");
    }
    header.azimuths[b] = littleEndian16(block + 2);
    if (header.azimuths[b] >= kFullTurn) {
      fail("block " + std::to_string(b) + " has azimuth " + std::to_string(header.azimuths[b]) +
           " (0.01° units), beyond 35999");
    }
  }
  const std::uint8_t* tail = packet.data() + kTailOffset;
  header.usec_past_hour = std::uint32_t(tail[0]) | std::uint32_t(tail[1]) << 8 |
                          std::uint32_t(tail[2]) << 16 | std::uint32_t(tail[3]) << 24;
  const std::uint8_t mode = tail[4];
  if (mode != 0x37 && mode != 0x38 && mode != 0x39) {
    fail("return mode byte " + hex(mode, 2) +
         " is none of 0x37 (strongest), 0x38 (last), 0x39 (dual)");
  }
  header.mode = Vlp16ReturnMode(mode);
  header.product = tail[5];
  // Velodyne lists 0x21 as the HDL-32E's, but VLP-16 captures hold it too (the outdoor test
  // fixture: 16 lasers, 0.4° a block at 10 Hz); an HDL-32E packet cannot be told from a VLP-16's
  // by its bytes alone, so 0x21 is read as a VLP-16 (docs/sensors.md).
  if (header.product != 0x22 && header.product != 0x21) {
    fail("product byte " + hex(header.product, 2) +
         " is not a VLP-16's (0x22, or 0x21 as some VLP-16 captures hold)");
  }
  return header;
}

Vlp16PacketHeader decodeVlp16Packet(std::span<const std::uint8_t> packet, double stamp,
                                    const Vlp16DecodeOptions& options, const std::string& file,
                                    const std::string& where, std::vector<Vlp16Point>& points,
                                    Vlp16ShotTally* tally) {
  const Vlp16PacketHeader header = readVlp16Header(packet, file, where);
  const bool dual = header.mode == Vlp16ReturnMode::kDual;
  const auto turns = blockTurns(header, dual, options.convention);
  constexpr int kLasers = sensors::Vlp16Layout::kLasers;
  const double pair_duration = 2.0 * sensors::Vlp16Layout::kSequenceDuration;
  for (int b = 0; b < kVlp16Blocks; ++b) {
    const int other_block = dual ? (b % 2 == 0 ? b + 1 : b - 1) : b;
    for (int sequence = 0; sequence < 2; ++sequence) {
      const int sequence_index = dual && options.convention == Vlp16Convention::kPerSequence
                                     ? (b - b % 2) + sequence
                                     : 2 * b + sequence;
      for (int laser = 0; laser < kLasers; ++laser) {
        const RawEcho own = echoAt(packet, b, sequence, laser);
        const RawEcho other = echoAt(packet, other_block, sequence, laser);
        const int ring = sensors::Vlp16Layout::ring(laser);
        if (tally && (!dual || b % 2 == 0)) {
          ++tally->shots[ring];
          if (own.count != 0 || other.count != 0) ++tally->echoed[ring];
        }
        if (own.count == 0) continue;                                  // no echo
        if (dual && b % 2 == 1 && other.count == own.count) continue;  // the pair's echo again
        const double distance = own.count * kVlp16DistanceUnit;
        if (!(distance > options.min_range && distance < options.max_range)) continue;
        const double in_pair = sequence * sensors::Vlp16Layout::kSequenceDuration +
                               laser * sensors::Vlp16Layout::kFiringInterval;
        const double exact = turns[b].azimuth + turns[b].step * in_pair / pair_duration;
        const auto azimuth = std::uint16_t(int(std::floor(exact + 0.5)) % kFullTurn);
        const double heading = azimuth * (std::numbers::pi / 18000.0);
        const double elevation =
            sensors::Vlp16Layout::kElevationDeg[laser] * (std::numbers::pi / 180.0);
        const double horizontal = distance * std::cos(elevation);
        Vlp16Point point;
        point.x = float(horizontal * std::cos(heading));
        point.y = float(-horizontal * std::sin(heading));  // clockwise azimuth: y is to the left
        point.z = float(distance * std::sin(elevation));
        point.distance = float(distance);
        point.azimuth = azimuth;
        point.intensity = own.reflectivity;
        point.laser = std::uint8_t(laser);
        point.ring = std::uint8_t(ring);
        point.echo = classifyEcho(own, other, header.mode);
        point.time = stamp + sequence_index * sensors::Vlp16Layout::kSequenceDuration +
                     laser * sensors::Vlp16Layout::kFiringInterval;
        points.push_back(point);
      }
    }
  }
  return header;
}

}  // namespace isg::formats
