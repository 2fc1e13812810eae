#include "formats/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "formats/mcap_writer.hpp"
#include "formats/ros2_message_decode.hpp"
#include "formats/ros2_messages.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;

// Three messages on two channels, written out of log-time order, in chunks of one message.
std::string writtenFile(const std::string& test, McapCompression compression) {
  const fs::path dir = test_files::scratchFolder(test);
  const fs::path path = dir / "t.mcap";
  McapWriterOptions options;
  options.compression = compression;
  options.chunk_size = 1;
  McapWriter mcap(path.string(), options);
  const std::uint16_t schema = mcap.addSchema("std_msgs/msg/String", "ros2msg", "string data\n");
  const std::uint16_t a = mcap.addChannel(schema, "/a", "cdr", {{"offered_qos_profiles", ""}});
  const std::uint16_t b = mcap.addChannel(schema, "/b", "cdr");
  mcap.write(a, 30, ros2::stringMessage("three"));
  mcap.write(b, 10, ros2::stringMessage("one"));
  mcap.write(a, 20, ros2::stringMessage("two"));
  mcap.close();
  std::string bytes = test_files::slurp(path);
  fs::remove_all(dir);
  return bytes;
}

std::vector<std::string> texts(McapReader& reader, const std::vector<std::string>& topics) {
  std::vector<std::string> out;
  reader.read(topics, [&](const McapMessageView& m) {
    out.push_back(m.channel->topic + " " + std::to_string(m.log_time_ns) + " " +
                  ros2::decodeString(m.data));
    return true;
  });
  return out;
}

std::string mcapErrorOf(const std::string& bytes) {
  try {
    McapReader reader(bytes, "t.mcap");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(read)";
}

TEST(McapReader, ReadsOurFilesInLogTimeOrderWhateverTheCompression) {
  for (const auto compression :
       {McapCompression::kNone, McapCompression::kZstd, McapCompression::kLz4}) {
    McapReader reader(writtenFile("mcap_read", compression), "t.mcap");
    EXPECT_EQ(reader.profile(), "ros2");
    EXPECT_EQ(reader.messageCount(), 3u);
    ASSERT_EQ(reader.channels().size(), 2u);
    const McapChannel& a = reader.channels()[0];
    EXPECT_EQ(a.topic, "/a");
    EXPECT_EQ(a.message_encoding, "cdr");
    EXPECT_EQ(a.schema_name, "std_msgs/msg/String");
    EXPECT_EQ(a.schema_encoding, "ros2msg");
    EXPECT_EQ(a.schema_data, "string data\n");
    EXPECT_EQ(a.metadata.at("offered_qos_profiles"), "");
    EXPECT_EQ(a.messages, 2u);
    EXPECT_EQ(reader.compressions(),
              std::vector<std::string>{std::string(compressionName(compression))});
    EXPECT_EQ(texts(reader, {}),
              (std::vector<std::string>{"/b 10 one", "/a 20 two", "/a 30 three"}));
    EXPECT_EQ(texts(reader, {"/a"}), (std::vector<std::string>{"/a 20 two", "/a 30 three"}));
  }
}

// A file of top-level records, laid out by hand: Header, Schema, Channel, an unknown record
// (0x80, which a reader must skip), two Messages, Data End, Footer.
std::string record(std::uint8_t opcode, const std::string& content) {
  std::string r(1, char(opcode));
  const std::uint64_t length = content.size();
  r.append(reinterpret_cast<const char*>(&length), 8);
  return r + content;
}
std::string str(const std::string& s) {
  const auto n = std::uint32_t(s.size());
  return std::string(reinterpret_cast<const char*>(&n), 4) + s;
}
template <typename T>
std::string num(T v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}
std::string message(std::uint16_t channel, std::uint64_t time, const std::string& data) {
  return record(0x05, num(channel) + num(std::uint32_t(0)) + num(time) + num(time) + data);
}
const std::string kMagic("\x89MCAP0\r\n", 8);
std::string handMade(const std::string& messages) {
  return kMagic + record(0x01, str("ros2") + str("by hand")) +
         record(0x03, num(std::uint16_t(1)) + str("std_msgs/msg/String") + str("ros2msg") +
                          str("string data\n")) +
         record(0x04, num(std::uint16_t(7)) + num(std::uint16_t(1)) + str("/chat") + str("cdr") +
                          num(std::uint32_t(0))) +
         record(0x80, "anything") + messages + record(0x0f, num(std::uint32_t(0))) +
         record(0x02, num(std::uint64_t(0)) + num(std::uint64_t(0)) + num(std::uint32_t(0))) +
         kMagic;
}

TEST(McapReader, ReadsTopLevelMessagesAndSkipsUnknownRecords) {
  McapReader reader(handMade(message(7, 5, ros2::stringMessage("late")) +
                             message(7, 2, ros2::stringMessage("early"))),
                    "t.mcap");
  EXPECT_EQ(reader.library(), "by hand");
  EXPECT_EQ(texts(reader, {}), (std::vector<std::string>{"/chat 2 early", "/chat 5 late"}));
}

TEST(McapReader, DamageIsAnErrorNamingItsByte) {
  EXPECT_EQ(mcapErrorOf("#ROSBAG V2.0\n"),
            "t.mcap: byte 0: not an MCAP file (it does not begin with MCAP's magic)");
  const std::string good = handMade(message(7, 5, ros2::stringMessage("x")));
  EXPECT_EQ(mcapErrorOf(good.substr(0, good.size() - 3)),
            "t.mcap: byte " + std::to_string(good.size() - 3) +
                ": cut short: the file does not end with MCAP's magic (a recording that was not "
                "closed; `mcap recover` mends it)");
  // A message on a channel nobody defined; a record longer than the file.
  const std::string stray = handMade(message(9, 5, ros2::stringMessage("x")));
  const std::size_t at = stray.find(std::string(1, '\x05') + num(std::uint64_t(32)));
  EXPECT_EQ(mcapErrorOf(stray), "t.mcap: byte " + std::to_string(at) +
                                    ": a message on channel 9, which no Channel record defines");
  std::string long_record = good;
  long_record[at + 1] = '\x7f';
  EXPECT_NE(mcapErrorOf(long_record)
                .find("t.mcap: byte " + std::to_string(at) +
                      ": a record (opcode 0x05) of 127 bytes, where "),
            std::string::npos)
      << mcapErrorOf(long_record);
  // A chunk whose CRC does not hold.
  std::string chunked = writtenFile("mcap_crc", McapCompression::kNone);
  const std::size_t text = chunked.find("three");
  chunked[text] = 'T';
  EXPECT_NE(mcapErrorOf(chunked).find("the chunk's records fail their CRC-32"), std::string::npos)
      << mcapErrorOf(chunked);
}

// A chunk's declared size is checked before anything is allocated for it: a few bytes that say
// they hold 1 GiB (a decompression bomb) are refused at once, naming the chunk's byte.
TEST(McapReader, AChunkDeclaringMoreThanTheLimitIsRefusedBeforeItIsRead) {
  const std::string chunk = num(std::uint64_t(0)) + num(std::uint64_t(0)) +
                            num(std::uint64_t(kMaxChunkBytes + 1)) + num(std::uint32_t(0)) +
                            str("zstd") + num(std::uint64_t(4)) + "zstd";
  const std::string bytes = handMade(record(0x06, chunk));
  const std::size_t at = bytes.find(std::string(1, '\x06') + num(std::uint64_t(chunk.size())));
  EXPECT_EQ(mcapErrorOf(bytes), "t.mcap: byte " + std::to_string(at) + ": a chunk of " +
                                    std::to_string(kMaxChunkBytes + 1) +
                                    " bytes uncompressed; at most 268435456 are read "
                                    "(docs/formats.md, \"Limits of recordings\")");
}

// The oracle: a file that npm's @mcap/core wrote (zstd chunks, CDR from
// @foxglove/rosmsg2-serialization, channel ids from 0), through formats/tests/npm_mcap_writer.js.
// Skipped where node or the npm oracles (ci/install-deps) are not installed.
TEST(McapReader, ReadsWhatNpmsWritersWrote) {
  const fs::path modules = fs::path(ISG_SOURCE_DIR) / "ci/oracles/node_modules";
  if (!fs::is_directory(modules / "@mcap/core") || std::system("node --version >/dev/null 2>&1")) {
    GTEST_SKIP() << "node or the npm oracles are not installed (ci/install-deps)";
  }
  const fs::path dir = test_files::scratchFolder("mcap_npm");
  const fs::path file = dir / "npm.mcap";
  const std::string command =
      "node " + (fs::path(ISG_SOURCE_DIR) / "formats/tests/npm_mcap_writer.js").string() + " " +
      file.string() + " " + modules.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  McapReader reader(file.string());
  EXPECT_EQ(reader.library(), "npm @mcap/core");
  EXPECT_EQ(reader.compressions(), std::vector<std::string>{"zstd"});
  ASSERT_EQ(reader.channels().size(), 1u);
  EXPECT_EQ(reader.channels()[0].schema_name, "geometry_msgs/msg/PoseStamped");
  int k = 0;
  reader.read({"/pose"}, [&](const McapMessageView& m) {
    const ros1::StampedPose pose = ros2::decodePoseStamped(m.data);
    EXPECT_EQ(m.sequence, std::uint32_t(k));
    EXPECT_EQ(pose.header.stamp.sec, 1700000000u + k);
    EXPECT_EQ(pose.header.stamp.nsec, 250000000u);
    EXPECT_EQ(m.log_time_ns, (1700000000ull + k) * 1000000000ull + 250000000ull);
    EXPECT_EQ(pose.header.frame_id, "map");
    EXPECT_EQ(pose.pose.translation(), Eigen::Vector3d(k, 2 * k, 0.5));
    EXPECT_NEAR(Eigen::AngleAxisd(pose.pose.linear()).angle(), 0.2 * k, 1e-12);
    ++k;
    return true;
  });
  EXPECT_EQ(k, 5);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
