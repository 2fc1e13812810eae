// The VLP-16 packet decoder against hand calculations: a packet built byte by byte from the
// manual's layout decodes to the azimuths, times, coordinates and echo kinds the manual gives,
// under both interpolations; a malformed packet is a named error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/input_error.hpp"
#include "formats/vlp16_packet.hpp"
#include "formats/vlp16_turns.hpp"

namespace isg::formats {
namespace {

// A dual-return packet whose block pairs start at azimuths 1.00°, 1.40°, … 3.00° (steps of 40).
class HandMadePacket {
 public:
  explicit HandMadePacket(std::uint8_t mode = 0x39) : bytes_(kVlp16PacketBytes, 0) {
    for (int b = 0; b < kVlp16Blocks; ++b) {
      bytes_[b * 100] = 0xFF;
      bytes_[b * 100 + 1] = 0xEE;
      setAzimuth(b, 100 + 40 * (mode == 0x39 ? b / 2 : b));
    }
    bytes_[1204] = mode;
    bytes_[1205] = 0x22;
  }
  void setAzimuth(int block, int azimuth) {
    bytes_[block * 100 + 2] = std::uint8_t(azimuth & 0xFF);
    bytes_[block * 100 + 3] = std::uint8_t(azimuth >> 8);
  }
  void setEcho(int block, int sequence, int laser, int count, int reflectivity) {
    const int at = block * 100 + 4 + 3 * (16 * sequence + laser);
    bytes_[at] = std::uint8_t(count & 0xFF);
    bytes_[at + 1] = std::uint8_t(count >> 8);
    bytes_[at + 2] = std::uint8_t(reflectivity);
  }
  std::span<const std::uint8_t> bytes() const { return bytes_; }
  std::vector<std::uint8_t>& raw() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

std::vector<Vlp16Point> decode(const HandMadePacket& packet, Vlp16Convention interpolation,
                               Vlp16ShotTally* tally = nullptr) {
  Vlp16DecodeOptions options;
  options.convention = interpolation;
  std::vector<Vlp16Point> points;
  decodeVlp16Packet(packet.bytes(), 100.0, options, "hand.pcap", "packet 0", points, tally);
  return points;
}

TEST(Vlp16Packet, ADualPacketDecodesAsTheManualSays) {
  HandMadePacket packet;
  // Pair 0, sequence 0, laser 0 (−15°): the last echo at 2.000 m (reflectivity 10) in block 0,
  // the strongest at 1.000 m (reflectivity 50) in block 1.
  packet.setEcho(0, 0, 0, 1000, 10);
  packet.setEcho(1, 0, 0, 500, 50);
  // Pair 0, sequence 1, laser 1 (+1°): one echo, 4.000 m, the same in both blocks.
  packet.setEcho(0, 1, 1, 2000, 7);
  packet.setEcho(1, 1, 1, 2000, 7);
  // Pair 2, sequence 0, laser 15 (+15°): an echo only in the pair's first block (0.3 m: dropped).
  packet.setEcho(4, 0, 15, 150, 90);
  Vlp16ShotTally tally;
  const auto points = decode(packet, Vlp16Convention::kPerSequence, &tally);
  ASSERT_EQ(points.size(), 3u);  // in the packet's order: block, sequence, laser

  const Vlp16Point& far = points[0];
  EXPECT_EQ(far.echo, Vlp16Echo::kFarWeak);
  EXPECT_EQ(far.azimuth, 100);  // the pair's azimuth at its first firing
  EXPECT_EQ(far.ring, 0);
  EXPECT_EQ(far.intensity, 10);
  EXPECT_DOUBLE_EQ(far.time, 100.0);
  const double c15 = std::cos(15.0 * std::numbers::pi / 180.0);
  const double s15 = std::sin(15.0 * std::numbers::pi / 180.0);
  const double a1 = 1.0 * std::numbers::pi / 180.0;
  EXPECT_FLOAT_EQ(far.x, float(2.0 * c15 * std::cos(a1)));
  EXPECT_FLOAT_EQ(far.y, float(-2.0 * c15 * std::sin(a1)));  // clockwise: to the right
  EXPECT_FLOAT_EQ(far.z, float(-2.0 * s15));

  const Vlp16Point& near = points[2];  // block 1: the same shot, the same azimuth and time
  EXPECT_EQ(near.echo, Vlp16Echo::kNearStrongest);
  EXPECT_EQ(near.azimuth, 100);
  EXPECT_DOUBLE_EQ(near.time, 100.0);
  EXPECT_FLOAT_EQ(near.distance, 1.0f);

  // Sequence 1, laser 1: 57.600 µs after the pair's start, of the pair's 110.592 µs turning
  // 0.40°: 1.00° + 0.40° · 57.600 / 110.592 = 1.2083° → 1.21°.
  const Vlp16Point& identical = points[1];
  EXPECT_EQ(identical.echo, Vlp16Echo::kIdentical);
  EXPECT_EQ(identical.azimuth, 121);
  EXPECT_EQ(identical.ring, 8);
  EXPECT_NEAR(identical.time, 100.0 + 55.296e-6 + 2.304e-6, 1e-12);

  // Dual mode: 6 pairs × 2 sequences = 12 shots per laser.
  EXPECT_EQ(tally.shots[0], 12u);
  EXPECT_EQ(tally.echoed[0], 1u);
  EXPECT_EQ(tally.echoed[8], 1u);
  EXPECT_EQ(tally.echoed[15], 1u);  // an echo, though nearer than the minimum range
  EXPECT_EQ(tally.echoed[3], 0u);
}

TEST(Vlp16Packet, NebulasInterpolationGivesTheSecondBlockTheNextPairsAzimuth) {
  HandMadePacket packet;
  packet.setEcho(0, 0, 0, 1000, 10);
  packet.setEcho(1, 0, 0, 500, 50);
  packet.setEcho(10, 1, 1, 700, 20);  // the last pair's first block, sequence 1
  const auto points = decode(packet, Vlp16Convention::kNebula);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0].azimuth, 100);
  EXPECT_EQ(points[1].azimuth, 140);                        // block 1 takes block 2's azimuth
  EXPECT_DOUBLE_EQ(points[1].time, 100.0 + 2 * 55.296e-6);  // the single-return table
  EXPECT_EQ(points[2].azimuth, 300);                        // no interpolation in block 10
  EXPECT_NEAR(points[2].time, 100.0 + 21 * 55.296e-6 + 2.304e-6, 1e-12);

  const auto per_sequence = decode(packet, Vlp16Convention::kPerSequence);
  ASSERT_EQ(per_sequence.size(), 3u);
  EXPECT_EQ(per_sequence[1].azimuth, 100);
  // Block 10 continues the previous pairs' 0.40° step: 3.00° + 0.40° · 57.6 / 110.592 → 3.21°.
  EXPECT_EQ(per_sequence[2].azimuth, 321);
  EXPECT_NEAR(per_sequence[2].time, 100.0 + 11 * 55.296e-6 + 2.304e-6, 1e-12);
}

TEST(Vlp16Packet, ASingleReturnPacketStepsEveryBlock) {
  HandMadePacket packet(0x37);
  packet.setEcho(11, 1, 14, 5000, 120);  // 10.000 m, in the packet's last sequence
  Vlp16ShotTally tally;
  const auto points = decode(packet, Vlp16Convention::kPerSequence, &tally);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].echo, Vlp16Echo::kStrongest);
  // Block 11 at 5.40°, the step of block 10 to 11 (0.40°) continued: 5.40 + 0.40 · 87.552 /
  // 110.592 = 5.7167° → 5.72°.
  EXPECT_EQ(points[0].azimuth, 572);
  EXPECT_NEAR(points[0].time, 100.0 + 23 * 55.296e-6 + 14 * 2.304e-6, 1e-12);
  EXPECT_EQ(tally.shots[14], 24u);
}

TEST(Vlp16Packet, AzimuthsWrapThroughZero) {
  HandMadePacket packet(0x37);
  for (int b = 0; b < kVlp16Blocks; ++b) packet.setAzimuth(b, (35900 + 40 * b) % 36000);
  for (int b = 0; b < kVlp16Blocks; ++b) packet.setEcho(b, 0, 1, 1000, 5);
  const auto points = decode(packet, Vlp16Convention::kPerSequence);
  ASSERT_EQ(points.size(), 12u);
  EXPECT_EQ(points[2].azimuth, 35981);  // 359.80° + 0.40° · 2.304 / 110.592
  EXPECT_EQ(points[3].azimuth, 21);
  const auto turns = cutIntoTurns(points, 0.0);
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_EQ(turns[0].points.size(), 3u);
  EXPECT_EQ(turns[1].points.size(), 9u);
  EXPECT_FALSE(turns[0].complete);
  const auto at_one_degree = cutIntoTurns(points, 1.0);  // 0.21° and 0.61° before the cut
  ASSERT_EQ(at_one_degree.size(), 2u);
  EXPECT_EQ(at_one_degree[0].points.size(), 5u);
}

std::string packetErrorOf(const std::vector<std::uint8_t>& bytes) {
  try {
    std::vector<Vlp16Point> points;
    decodeVlp16Packet(bytes, 0.0, {}, "lab.pcap", "UDP datagram 7", points);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Vlp16Packet, AMalformedPacketIsANamedError) {
  HandMadePacket packet;
  auto bytes = packet.raw();
  bytes.resize(1000);
  EXPECT_EQ(packetErrorOf(bytes),
            "lab.pcap: UDP datagram 7: has 1000 bytes, a VLP-16 data packet has 1206");
  bytes = packet.raw();
  bytes[300] = 0xDD;
  EXPECT_EQ(packetErrorOf(bytes),
            "lab.pcap: UDP datagram 7: block 3 starts 0xDD 0xEE, not FF EE (not a VLP-16 data "
            "packet)");
  bytes = packet.raw();
  bytes[1204] = 0x3B;
  EXPECT_EQ(packetErrorOf(bytes),
            "lab.pcap: UDP datagram 7: return mode byte 0x3B is none of 0x37 (strongest), 0x38 "
            "(last), 0x39 (dual)");
  bytes = packet.raw();
  bytes[1205] = 0x28;
  EXPECT_EQ(packetErrorOf(bytes),
            "lab.pcap: UDP datagram 7: product byte 0x28 is not a VLP-16's (0x22, or 0x21 as some "
            "VLP-16 captures hold)");
  bytes = packet.raw();
  bytes[2] = 0xA0;
  bytes[3] = 0x8C;  // 36000
  EXPECT_EQ(packetErrorOf(bytes),
            "lab.pcap: UDP datagram 7: block 0 has azimuth 36000 (0.01° units), beyond 35999");
}

}  // namespace
}  // namespace isg::formats
