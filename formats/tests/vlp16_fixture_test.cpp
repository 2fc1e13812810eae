// The decoder on real VLP-16 recordings (formats/tests/data/vlp16-real, with their licences):
// tier4/nebula's decoded cloud reproduced from its raw-packet ROS 2 bag, and the real sensor's
// return statistics that the simulated one is compared with (docs/simulation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "formats/pcap_file.hpp"
#include "formats/pcd_reader.hpp"
#include "formats/ros2_bag.hpp"
#include "formats/velodyne_scan_cdr.hpp"
#include "formats/vlp16_recording.hpp"
#include "formats/vlp16_statistics.hpp"
#include "sensors/vlp16_layout.hpp"

namespace isg::formats {
namespace {

const std::string kData = std::string(ISG_SOURCE_DIR) + "/formats/tests/data/vlp16-real/";
const std::string kIndoorVlp16Bag = kData + "nebula-vlp16-indoor.db3";
const std::string kOutdoorPcap = kData + "rust-lidar-utils-vlp16-outdoor.pcap";

std::span<const std::uint8_t> bytesOf(const std::string& data) {
  return {reinterpret_cast<const std::uint8_t*>(data.data()), data.size()};
}

// nebula's code for an echo kind. Its "first" echo is the farther one of a dual pair (it compares
// the distance counts), so its FIRST_* are our far echoes.
int nebulaReturnType(Vlp16Echo echo) {
  switch (echo) {
    case Vlp16Echo::kStrongest:
      return 3;
    case Vlp16Echo::kLast:
      return 1;
    case Vlp16Echo::kIdentical:
      return 6;
    case Vlp16Echo::kFarWeak:
      return 4;
    case Vlp16Echo::kNearWeak:
      return 5;
    case Vlp16Echo::kFarStrongest:
      return 9;
    case Vlp16Echo::kNearStrongest:
      return 10;
  }
  return 0;
}

TEST(Vlp16Fixture, TheIndoorBagHoldsFourScansOfRawPackets) {
  const Ros2Bag bag(kIndoorVlp16Bag);
  ASSERT_EQ(bag.topics().size(), 1u);
  EXPECT_EQ(bag.topics()[0].name, "/velodyne_packets");
  EXPECT_EQ(bag.topics()[0].type, "velodyne_msgs/msg/VelodyneScan");
  EXPECT_EQ(bag.topics()[0].messages, 4u);
  const auto messages = bag.messages("/velodyne_packets");
  ASSERT_EQ(messages.size(), 4u);
  EXPECT_EQ(messages[3].stamp_ns, 1673400472138016708);
  std::vector<std::size_t> packets;
  for (std::size_t m = 0; m < messages.size(); ++m) {
    const auto scan = decodeVelodyneScanCdr(messages[m].data, kIndoorVlp16Bag, "message");
    EXPECT_EQ(scan.frame_id, "velodyne");
    packets.push_back(scan.packets.size());
    if (m == 0) {
      EXPECT_DOUBLE_EQ(scan.packets[0].stamp, 1673400471.737763166);
    }
  }
  EXPECT_EQ(packets, (std::vector<std::size_t>{151, 151, 151, 150}));
  // The bag's folder reads the same (its .db3 files in name order).
  const Ros2Bag folder(kData);
  ASSERT_EQ(folder.topics().size(), 1u);
  EXPECT_EQ(folder.topics()[0].messages, 4u);
  EXPECT_EQ(folder.messages("/velodyne_packets")[3].data, messages[3].data);
}

TEST(Vlp16Fixture, NebulasDecodedCloudIsReproduced) {
  // As nebula's test ran its decoder: minimum range 0.3 m, maximum 300 m, its interpolation, and
  // the packets stamped with whole seconds (their fractional part dropped), which left each
  // point's time_stamp its firing's offset in its packet: here each packet is stamped 0.
  Vlp16DecodeOptions options;
  options.min_range = 0.3;
  options.max_range = 300.0;
  options.convention = Vlp16Convention::kNebula;
  const Ros2Bag bag(kIndoorVlp16Bag);
  std::vector<Vlp16Point> points;
  for (const auto& message : bag.messages("/velodyne_packets")) {
    for (const auto& packet :
         decodeVelodyneScanCdr(message.data, kIndoorVlp16Bag, "message").packets) {
      decodeVlp16Packet(bytesOf(packet.data), 0.0, options, kIndoorVlp16Bag, "packet", points);
    }
  }
  const auto turns = cutIntoTurns(points, 0.0);
  ASSERT_EQ(turns.size(), 5u);  // 603 packets: 4 turns from 0.66°, the fifth just begun
  const std::vector<Vlp16Point>& ours = turns[3].points;

  const PcdColumns expected = readPcdColumns(kData + "nebula-vlp16-indoor.decoded.pcd");
  const std::size_t n = expected["x"].size();
  ASSERT_EQ(n, 14831u);
  // nebula kept the turn's last degree for the next cloud: our turn holds 40 more points, all
  // from 359.05° on.
  ASSERT_EQ(ours.size(), n + 40);
  for (std::size_t i = n; i < ours.size(); ++i) EXPECT_GE(ours[i].azimuth, 35900) << i;

  // Floats within 1e-6 of the distance (a few ulps: nebula computes in float with float tables);
  // the time within 240 ns, one step of a double holding seconds since the epoch (2^-22 s), which
  // nebula's overflow arithmetic adds to the points carried into the next cloud.
  auto near = [](double a, double b, double scale) {
    return std::abs(a - b) <= 1e-6 * std::max(1.0, scale);
  };
  std::size_t mismatched = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vlp16Point& p = ours[i];
    const double elevation =
        sensors::Vlp16Layout::kElevationDeg[p.laser] * std::numbers::pi / 180.0;
    const bool same =
        near(p.x, expected["x"][i], p.distance) && near(p.y, expected["y"][i], p.distance) &&
        near(p.z, expected["z"][i], p.distance) && p.intensity == expected["intensity"][i] &&
        nebulaReturnType(p.echo) == expected["return_type"][i] &&
        p.ring == expected["channel"][i] &&
        near(p.azimuth * std::numbers::pi / 18000.0, expected["azimuth"][i], 1.0) &&
        std::abs(std::sin(elevation) - expected["elevation"][i]) < 1e-7 &&
        near(p.distance, expected["distance"][i], p.distance) &&
        std::abs(p.time * 1e9 - expected["time_stamp"][i]) <= 240.0;
    if (!same && ++mismatched <= 5) {
      ADD_FAILURE() << "point " << i << ": ours x " << p.x << " y " << p.y << " z " << p.z
                    << " intensity " << int(p.intensity) << " ring " << int(p.ring) << " azimuth "
                    << p.azimuth << " time " << p.time * 1e9 << " ns; nebula x " << expected["x"][i]
                    << " y " << expected["y"][i] << " z " << expected["z"][i] << " intensity "
                    << expected["intensity"][i] << " channel " << expected["channel"][i]
                    << " azimuth " << expected["azimuth"][i] << " time "
                    << expected["time_stamp"][i];
    }
  }
  EXPECT_EQ(mismatched, 0u);
}

TEST(Vlp16Fixture, ThePerSequenceInterpolationKeepsEveryEchoAndMovesItsAzimuthAtMostOnePair) {
  Vlp16DecodeOptions nebula;
  nebula.convention = Vlp16Convention::kNebula;
  const auto a = readVlp16Recording(kIndoorVlp16Bag, {});
  const auto b = readVlp16Recording(kIndoorVlp16Bag, nebula);
  ASSERT_EQ(a.points.size(), b.points.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.points[i].distance, b.points[i].distance) << i;
    ASSERT_EQ(a.points[i].intensity, b.points[i].intensity) << i;
    ASSERT_EQ(a.points[i].echo, b.points[i].echo) << i;
    const int step = std::abs(int(a.points[i].azimuth) - int(b.points[i].azimuth));
    const int turned = std::min(step, 36000 - step);
    EXPECT_LE(turned, 45) << i;  // a pair turns 0.38–0.41° here
    moved += turned != 0;
  }
  // nebula's quirks touch the second block of every pair with two echoes and the last pair.
  EXPECT_GT(moved, 0u);
  EXPECT_LT(double(moved) / double(a.points.size()), 0.3);
}

TEST(Vlp16Fixture, TheIndoorSensorLosesHalfItsShotsMostlyTheLowLasersBlockedByTheMount) {
  const auto recording = readVlp16Recording(kIndoorVlp16Bag, {});
  EXPECT_EQ(recording.data_packets, 603u);
  EXPECT_EQ(recording.mode, Vlp16ReturnMode::kDual);
  const auto stats = vlp16Statistics(recording.tally, cutIntoTurns(recording.points, 0.0));
  EXPECT_EQ(stats.complete_turns, 3);
  // 49.3 % of the shots have no echo in either block (49.5 % of the packets' echo slots are
  // empty, the second block of a pair being empty more often).
  EXPECT_NEAR(stats.lost, 0.493, 0.001);
  EXPECT_NEAR(stats.lost_by_ring[0], 1.00, 0.005);  // −15°
  EXPECT_NEAR(stats.lost_by_ring[1], 0.99, 0.01);   // −13°
  EXPECT_NEAR(stats.lost_by_ring[2], 0.85, 0.01);   // −11°
  for (int ring = 8; ring < 16; ++ring) EXPECT_LT(stats.lost_by_ring[ring], 0.35) << ring;
  // Calibrated reflectivity: diffuse indoor surfaces, nothing retroreflective.
  EXPECT_NEAR(stats.intensity_median, 32, 3);
  EXPECT_NEAR(stats.intensity_p99, 100, 5);
  EXPECT_LT(stats.intensity_max, 128);
  std::printf("indoor: lost %.3f; by ring", stats.lost);
  for (double l : stats.lost_by_ring) std::printf(" %.3f", l);
  std::printf("; intensity median %.0f p99 %.0f max %.0f; %.0f points per turn over %.4f s\n",
              stats.intensity_median, stats.intensity_p99, stats.intensity_max,
              stats.points_per_turn, stats.turn_duration);
}

TEST(Vlp16Fixture, TheOutdoorPcapHoldsDataAndPositionPackets) {
  std::size_t skipped = 0;
  const auto datagrams = readPcapUdp(kOutdoorPcap, &skipped);
  EXPECT_EQ(datagrams.size(), 100u);
  EXPECT_EQ(skipped, 0u);
  EXPECT_EQ(datagrams[0].destination_port, 2368);
  EXPECT_DOUBLE_EQ(datagrams[0].stamp, 1415644617.383637);
  const auto recording = readVlp16Recording(kOutdoorPcap, {});
  EXPECT_EQ(recording.data_packets, 84u);
  EXPECT_EQ(recording.position_packets, 16u);
  EXPECT_EQ(recording.mode, Vlp16ReturnMode::kStrongest);
  const auto turns = cutIntoTurns(recording.points, 0.0);
  ASSERT_EQ(turns.size(), 2u);  // from 250.35° round to 290.8°: no complete turn
  const auto stats = vlp16Statistics(recording.tally, turns);
  EXPECT_EQ(stats.complete_turns, 0);
  // Outdoors the lower lasers see the ground and lose almost nothing; the upper ones see sky.
  EXPECT_NEAR(stats.lost, 0.393, 0.001);
  for (int ring = 0; ring < 5; ++ring) EXPECT_LT(stats.lost_by_ring[ring], 0.05) << ring;
  for (int ring = 8; ring < 16; ++ring) EXPECT_GT(stats.lost_by_ring[ring], 0.45) << ring;
  EXPECT_NEAR(stats.intensity_median, 7, 1);
  EXPECT_NEAR(stats.intensity_p99, 100, 5);
  EXPECT_EQ(stats.intensity_max, 213);  // a retroreflector: above the diffuse scale's 100
  std::printf("outdoor: lost %.3f; by ring", stats.lost);
  for (double l : stats.lost_by_ring) std::printf(" %.3f", l);
  std::printf("; %zu points\n", recording.points.size());
}

std::string pcapError(const std::string& bytes) {
  try {
    parsePcapUdp(bytes, "lab.pcap");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string fileBytes(const std::string& path) { return common::readCheckedFile(path, 1u << 24); }

TEST(Vlp16Fixture, DamagedCapturesAndBagsAreNamedErrors) {
  const std::string pcap = fileBytes(kOutdoorPcap);
  EXPECT_EQ(pcapError(pcap.substr(0, 100)),
            "lab.pcap: record 0: announces 1248 bytes, the file holds 60");
  EXPECT_EQ(pcapError(pcap.substr(0, 10)),
            "lab.pcap: holds 10 bytes, fewer than a pcap header's 24");
  EXPECT_EQ(pcapError("\x0a\x0d\x0d\x0a" + pcap.substr(4)),
            "lab.pcap: not a pcap file (magic 0x0A0D0D0A; pcapng is not read: save as pcap, e.g. "
            "editcap -F pcap)");

  const auto message = Ros2Bag(kIndoorVlp16Bag).messages("/velodyne_packets")[0];
  try {
    decodeVelodyneScanCdr(std::string_view(message.data).substr(0, 5000), "b.db3", "message 0");
    ADD_FAILURE() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_STREQ(e.what(), "b.db3: message 0: 151 packets announced, the message holds at most 4");
  }
  try {
    Ros2Bag(kIndoorVlp16Bag).messages("/points");
    ADD_FAILURE() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              kIndoorVlp16Bag + ": no topic /points (the bag has: /velodyne_packets)");
  }
  try {
    Ros2Bag bag(kOutdoorPcap);
    ADD_FAILURE() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              kOutdoorPcap + ": not a ROS 2 bag database (file is not a database)");
  }
}

}  // namespace
}  // namespace isg::formats
