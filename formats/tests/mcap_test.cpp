// The MCAP writer and the ROS 2 CDR messages on their own, against hand-laid bytes;
// cli/tests/mcap_oracle.py reads a whole exported dataset with npm's MCAP readers.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "common/input_error.hpp"
#include "formats/cdr_writer.hpp"
#include "formats/mcap_writer.hpp"
#include "formats/ros2_messages.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;
using test_files::slurp;

template <typename T>
T recordAt(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

TEST(Crc32, IsTheCheckValueOfIsoHdlcAndContinues) {
  EXPECT_EQ(crc32("123456789"), 0xcbf43926u);  // the CRC catalogue's check value
  EXPECT_EQ(crc32("56789", crc32("1234")), 0xcbf43926u);
}

TEST(CdrWriter, AlignsEachPrimitiveToItsSizeAfterTheEncapsulationHeader) {
  CdrWriter out;
  out.u8(7);
  out.f64(1.5);      // 7 bytes of padding: at 8 of the body
  out.string("ab");  // at 16: count 3, 'a' 'b' NUL
  out.u16(9);        // at 23, aligned to 24
  const std::string& bytes = out.data();
  ASSERT_EQ(bytes.size(), 4u + 26u);
  EXPECT_EQ(bytes.substr(0, 4), std::string("\x00\x01\x00\x00", 4));
  EXPECT_EQ(bytes[4], 7);
  EXPECT_EQ(recordAt<double>(bytes, 4 + 8), 1.5);
  EXPECT_EQ(recordAt<std::uint32_t>(bytes, 4 + 16), 3u);
  EXPECT_EQ(bytes.substr(4 + 20, 3), std::string("ab\0", 3));
  EXPECT_EQ(recordAt<std::uint16_t>(bytes, 4 + 24), 9u);
}

TEST(Ros2Messages, TfMessageLaidOutByHand) {
  ros2::StampedTransform t;
  t.stamp = {1000000001, 5};
  t.parent = "a";
  t.child = "b";
  t.parent_T_child.translation() = Eigen::Vector3d(1, 2, 3);
  t.parent_T_child.linear() = Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const std::string bytes = ros2::tfMessage({t});
  // Body: count (0), sec (4), nanosec (8), "a" (12: 4 + 2), "b" (20: 4 + 2), translation (32),
  // rotation (56), end 88.
  ASSERT_EQ(bytes.size(), 4u + 88u);
  EXPECT_EQ(recordAt<std::uint32_t>(bytes, 4), 1u);
  EXPECT_EQ(recordAt<std::int32_t>(bytes, 8), 1000000001);
  EXPECT_EQ(recordAt<std::uint32_t>(bytes, 12), 5u);
  EXPECT_EQ(bytes.substr(16, 6), std::string("\x02\x00\x00\x00"
                                             "a\0",
                                             6));
  EXPECT_EQ(bytes.substr(24, 6), std::string("\x02\x00\x00\x00"
                                             "b\0",
                                             6));
  EXPECT_EQ(recordAt<double>(bytes, 36), 1.0);
  EXPECT_EQ(recordAt<double>(bytes, 52), 3.0);
  // −0.5 rad about z, w kept positive: (0, 0, −sin 0.25, cos 0.25).
  EXPECT_NEAR(recordAt<double>(bytes, 76), -std::sin(0.25), 1e-15);
  EXPECT_NEAR(recordAt<double>(bytes, 84), std::cos(0.25), 1e-15);
}

TEST(Ros2Messages, DefinitionsNameEveryTypeTheyUse) {
  const ros2::MessageType odometry = ros2::odometryType();
  EXPECT_EQ(odometry.name, "nav_msgs/msg/Odometry");
  EXPECT_EQ(odometry.definition.rfind("std_msgs/Header header\nstring child_frame_id\n", 0), 0u);
  for (const char* used :
       {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/Pose", "geometry_msgs/Point",
        "geometry_msgs/Quaternion", "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist",
        "geometry_msgs/Vector3", "geometry_msgs/PoseWithCovariance"}) {
    EXPECT_NE(odometry.definition.find(std::string(80, '=') + "\nMSG: " + used + "\n"),
              std::string::npos)
        << used;
  }
}

// The file's layout read back by hand: magic, Header, chunks, Data End (its CRC), the summary
// (its CRC), the Footer, magic.
TEST(McapWriter, LaysOutAnIndexedFileWithItsCrcs) {
  const fs::path dir = test_files::scratchFolder("mcap_layout");
  const fs::path path = dir / "t.mcap";
  McapWriterOptions options;
  options.compression = McapCompression::kNone;
  options.chunk_size = 1;  // a chunk per message
  {
    McapWriter mcap(path.string(), options);
    const std::uint16_t schema = mcap.addSchema("std_msgs/msg/String", "ros2msg", "string data\n");
    const std::uint16_t a = mcap.addChannel(schema, "/a", "cdr");
    const std::uint16_t b = mcap.addChannel(schema, "/b", "cdr");
    mcap.write(a, 10, ros2::stringMessage("one"));
    mcap.write(b, 20, ros2::stringMessage("two"));
    mcap.write(a, 30, ros2::stringMessage("three"));
    EXPECT_FALSE(fs::exists(path));  // nothing at the path before close()
    mcap.close();
    EXPECT_EQ(mcap.counts(), (std::vector<std::uint64_t>{2, 1}));
    const std::string closed = slurp(path);
    mcap.close();  // a second close writes nothing
    EXPECT_EQ(slurp(path), closed);
    EXPECT_THROW(mcap.write(a, 40, ros2::stringMessage("late")), std::logic_error);
  }
  const std::string file = slurp(path);
  const std::string magic("\x89MCAP0\r\n", 8);
  ASSERT_GT(file.size(), 2 * magic.size() + 29);
  EXPECT_EQ(file.substr(0, 8), magic);
  EXPECT_EQ(file.substr(file.size() - 8), magic);
  // Footer: opcode, length 20, summary start, summary offset start, summary CRC.
  const std::size_t footer = file.size() - 8 - 29;
  EXPECT_EQ(file[footer], 0x02);
  EXPECT_EQ(recordAt<std::uint64_t>(file, footer + 1), 20u);
  const auto summary_start = recordAt<std::uint64_t>(file, footer + 9);
  const auto summary_offset_start = recordAt<std::uint64_t>(file, footer + 17);
  EXPECT_EQ(recordAt<std::uint32_t>(file, footer + 25),
            crc32(file.substr(summary_start, footer + 25 - summary_start)));
  // Data End right before the summary, with the CRC of everything before it.
  const std::size_t data_end = summary_start - 13;
  EXPECT_EQ(file[data_end], 0x0f);
  EXPECT_EQ(recordAt<std::uint32_t>(file, data_end + 9), crc32(file.substr(0, data_end)));
  // The summary starts with the schema, then the two channels; a Summary Offset per group
  // (schemas, channels, statistics, chunk indexes).
  EXPECT_EQ(file[summary_start], 0x03);
  EXPECT_EQ((footer - summary_offset_start) % 26, 0u);
  EXPECT_EQ((footer - summary_offset_start) / 26, 4u);
  // Statistics: 3 messages, 1 schema, 2 channels, 3 chunks, from 10 to 30 ns.
  std::size_t offset = summary_start;
  while (file[offset] != 0x0b) offset += 9 + recordAt<std::uint64_t>(file, offset + 1);
  EXPECT_EQ(recordAt<std::uint64_t>(file, offset + 9), 3u);
  EXPECT_EQ(recordAt<std::uint16_t>(file, offset + 17), 1u);
  EXPECT_EQ(recordAt<std::uint32_t>(file, offset + 19), 2u);
  EXPECT_EQ(recordAt<std::uint32_t>(file, offset + 31), 3u);
  EXPECT_EQ(recordAt<std::uint64_t>(file, offset + 35), 10u);
  EXPECT_EQ(recordAt<std::uint64_t>(file, offset + 43), 30u);
  fs::remove_all(dir);
}

TEST(McapWriter, LeavesNothingWithoutClose) {
  const fs::path dir = test_files::scratchFolder("mcap_unclosed");
  {
    McapWriter mcap((dir / "t.mcap").string(), {});
    mcap.write(mcap.addChannel(mcap.addSchema("s", "ros2msg", ""), "/a", "cdr"), 1, "x");
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(McapWriter, RefusesToReplaceAFileItDidNotWrite) {
  const fs::path dir = test_files::scratchFolder("mcap_refuse");
  { std::ofstream(dir / "notes.mcap") << "mine"; }
  McapWriterOptions options;
  options.overwrite = true;
  EXPECT_THROW(McapWriter((dir / "notes.mcap").string(), options), common::InputError);
  EXPECT_EQ(slurp(dir / "notes.mcap"), "mine");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
