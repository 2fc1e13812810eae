// The ROS 1 bag reader: our own writer's bags read back, bags written by Debian's python3-rosbag
// (plain, bz2 and lz4 chunks; formats/tests/python_rosbag.py) read in the order rosbag's own
// reader gives, and damaged bags refused with the exact reason.

#include "formats/rosbag_reader.hpp"
#include "common/input_error.hpp"
#include "formats/rosbag_writer.hpp"
#include "formats/tests/scratch_files.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

namespace isg::formats {
namespace {

namespace fs = std::filesystem;
using test_files::slurp;

fs::path readerScratch(const std::string& name) {
  return test_files::scratchFolder("rosbag_reader_" + name);
}

std::string hex(std::string_view bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : bytes) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

// Each message as "topic sec nsec hex", in the order read.
std::vector<std::string> listing(RosbagReader& reader,
                                 const std::vector<std::string>& topics = {}) {
  std::vector<std::string> out;
  reader.read(topics, [&](const BagMessageView& m) {
    out.push_back(m.connection->topic + " " + std::to_string(m.time.sec) + " " +
                  std::to_string(m.time.nsec) + " " + hex(m.data));
    return true;
  });
  return out;
}

// A bag of our writer's: three topics, 300 messages of 3–5 kB over several chunks, two topics'
// times interleaved and the third's behind them.
struct WrittenBag {
  fs::path path;
  std::vector<std::string> in_time_order;
};

WrittenBag writeOurs(const fs::path& dir) {
  WrittenBag bag{dir / "ours.bag", {}};
  RosbagWriter writer(bag.path.string(), false);
  const RosMessageType text{"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data\n"};
  const int a = writer.connect("/a", text, true);
  const int b = writer.connect("/b", text);
  const int c = writer.connect("/c", text);
  std::vector<std::tuple<RosTime, int, std::string>> written;
  for (int i = 0; i < 100; ++i) {
    const std::string payload(3000 + 20 * i, char('a' + i % 26));
    const RosTime t{10 + std::uint32_t(i / 10), std::uint32_t(i % 10) * 100000000u};
    const RosTime t_late{t.sec - 2, t.nsec};  // two seconds behind
    writer.write(a, t, payload);
    writer.write(b, t, payload + "b");
    if (i >= 20) writer.write(c, t_late, payload + "c");
    written.emplace_back(t, a, payload);
    written.emplace_back(t, b, payload + "b");
    if (i >= 20) written.emplace_back(t_late, c, payload + "c");
  }
  writer.close();
  // Time order, ties by connection (all three have distinct connection numbers).
  std::stable_sort(written.begin(), written.end(), [](const auto& x, const auto& y) {
    if (std::get<0>(x) < std::get<0>(y) || std::get<0>(y) < std::get<0>(x))
      return std::get<0>(x) < std::get<0>(y);
    return std::get<1>(x) < std::get<1>(y);
  });
  const char* topics[] = {"/a", "/b", "/c"};
  for (const auto& [t, connection, payload] : written) {
    bag.in_time_order.push_back(std::string(topics[connection]) + " " + std::to_string(t.sec) +
                                " " + std::to_string(t.nsec) + " " + hex(payload));
  }
  return bag;
}

TEST(RosbagReader, ReadsOurOwnBagsBackInTimeOrder) {
  const fs::path dir = readerScratch("ours");
  const WrittenBag bag = writeOurs(dir);
  RosbagReader reader(bag.path.string());
  ASSERT_EQ(reader.connections().size(), 3u);
  EXPECT_EQ(reader.connections()[0].topic, "/a");
  EXPECT_TRUE(reader.connections()[0].latching);
  EXPECT_FALSE(reader.connections()[1].latching);
  EXPECT_EQ(reader.connections()[2].type.datatype, "std_msgs/String");
  EXPECT_EQ(reader.connections()[2].type.md5sum, "992ce8a1687cec8c8bd883ec73ca41d1");
  EXPECT_EQ(reader.connections()[2].type.definition, "string data\n");
  EXPECT_EQ(reader.connections()[2].callerid, "/isg_export");
  EXPECT_EQ(reader.connections()[0].messages, 100u);
  EXPECT_EQ(reader.connections()[2].messages, 80u);
  EXPECT_EQ(reader.messageCount(), 280u);
  EXPECT_EQ(reader.compressions(), std::vector<std::string>{"none"});
  EXPECT_EQ(reader.startTime().sec, 10u);  // /c's first, two seconds behind /a's 12 s
  EXPECT_EQ(reader.endTime().sec, 19u);
  EXPECT_EQ(reader.endTime().nsec, 900000000u);
  EXPECT_EQ(listing(reader), bag.in_time_order);
  // A topic alone, and a visitor that stops.
  std::vector<std::string> only_c;
  for (const auto& line : bag.in_time_order) {
    if (line.rfind("/c ", 0) == 0) only_c.push_back(line);
  }
  EXPECT_EQ(listing(reader, {"/c"}), only_c);
  int seen = 0;
  reader.read({}, [&](const BagMessageView& m) {
    EXPECT_EQ(m.index, std::uint64_t(seen));
    return ++seen < 5;
  });
  EXPECT_EQ(seen, 5);
  // The same bytes from memory.
  RosbagReader in_memory(slurp(bag.path), "memory.bag");
  EXPECT_EQ(listing(in_memory), bag.in_time_order);
  fs::remove_all(dir);
}

TEST(RosbagReader, ReadsPythonRosbagsPlainBz2AndLz4AsRosbagDoes) {
  const fs::path dir = readerScratch("python");
  for (const std::string compression : {"none", "bz2", "lz4"}) {
    SCOPED_TRACE(compression);
    const fs::path bag = dir / (compression + ".bag"), expected = dir / (compression + ".txt");
    const std::string command = "/usr/bin/python3 '" + std::string(ISG_SOURCE_DIR) +
                                "/formats/tests/python_rosbag.py' '" + bag.string() + "' " +
                                compression + " '" + expected.string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::vector<std::string> lines;
    std::istringstream in(slurp(expected));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_EQ(lines.size(), 122u);  // 60 + 50 + 12
    RosbagReader reader(bag.string());
    EXPECT_EQ(reader.compressions(), std::vector<std::string>{compression});
    EXPECT_EQ(reader.connections().size(), 3u);
    EXPECT_EQ(reader.messageCount(), 122u);
    EXPECT_EQ(listing(reader), lines);
  }
  fs::remove_all(dir);
}

// The bytes of a bag with `field=`'s value (of `size` bytes) overwritten.
std::string patched(std::string bytes, const std::string& field, const std::string& value) {
  const std::size_t at = bytes.find(field + "=");
  EXPECT_NE(at, std::string::npos) << field;
  bytes.replace(at + field.size() + 1, value.size(), value);
  return bytes;
}

std::string bagErrorOf(std::string bytes) {
  try {
    RosbagReader reader(std::move(bytes), "x.bag");
    reader.read({}, [](const BagMessageView&) { return true; });
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RosbagReader, RefusesDamagedBagsWithTheReason) {
  const fs::path dir = readerScratch("damaged");
  const std::string bag = slurp(writeOurs(dir).path);
  EXPECT_EQ(bagErrorOf("hello"), "x.bag: not a ROS 1 bag: it does not start with \"#ROSBAG V2.0\"");
  EXPECT_EQ(bagErrorOf("#ROSBAG V1.2\n" + std::string(100, '\0')),
            "x.bag: a ROS bag of version 1.2: only version 2.0 is read (rosbag fix converts older "
            "bags)");
  EXPECT_EQ(bagErrorOf(patched(bag, "index_pos", std::string(8, '\0'))),
            "x.bag: the bag is not indexed (its recording was cut short): `rosbag reindex` mends "
            "it");
  // Cut in half: the index the header points at is gone.
  const std::string half = bag.substr(0, bag.size() / 2);
  std::uint64_t index_position;
  std::memcpy(&index_position, bag.data() + bag.find("index_pos=") + 10, 8);
  EXPECT_EQ(bagErrorOf(half), "x.bag: byte 13: the bag header's index position " +
                                  std::to_string(index_position) +
                                  " lies outside the file (truncated?)");
  // An unknown compression, named with where its chunk is.
  const std::size_t chunk = 13 + 4096;  // the first chunk: after the version line and the header
  EXPECT_EQ(bagErrorOf(patched(bag, "compression", "zstd")),
            "x.bag: byte " + std::to_string(chunk) +
                ": chunk compression \"zstd\" is not supported (none, bz2 and lz4 are)");
  // A message's bytes changed under its index: the record is no longer a message.
  std::string moved = bag;
  const std::size_t first_message = moved.find("op=\x02");
  ASSERT_NE(first_message, std::string::npos);
  moved[first_message + 3] = '\x07';
  EXPECT_NE(bagErrorOf(moved).find("the index points at a record that is not a message"),
            std::string::npos)
      << bagErrorOf(moved);
  EXPECT_THROW(RosbagReader((dir / "missing.bag").string()), common::InputError);
  // A chunk that declares more than a chunk may hold is refused before it is read (ROS 1 chunk
  // sizes had no cap: a 17.5 kB bag of bz2 zeros cost gigabytes).
  const std::uint32_t too_large = std::uint32_t(kMaxChunkBytes + 1);
  EXPECT_EQ(
      bagErrorOf(patched(bag, "size", std::string(reinterpret_cast<const char*>(&too_large), 4))),
      "x.bag: byte " + std::to_string(chunk) + ": a chunk of " + std::to_string(too_large) +
          " bytes uncompressed; at most 268435456 are read (docs/formats.md, \"Limits of "
          "recordings\")");
  // A compressed chunk that claims one byte more, or one less, than its data holds.
  for (const std::string compression : {"bz2", "lz4"}) {
    const std::string python =
        slurp(std::string(ISG_SOURCE_DIR) + "/formats/fuzz/corpus/rosbag_fuzzer/python-" +
              compression + ".bag");
    const std::size_t size_at = python.find("size=") + 5;
    std::uint32_t size;
    std::memcpy(&size, python.data() + size_at, 4);
    for (const std::uint32_t claimed : {size + 1, size - 1}) {
      std::string lying = python;
      std::memcpy(lying.data() + size_at, &claimed, 4);
      const std::string error = bagErrorOf(lying);
      const std::string expected =
          "chunk does not decompress to its " + std::to_string(claimed) + " bytes (" +
          (claimed > size ? "it holds " + std::to_string(size) : std::string("it holds more")) +
          ")";
      EXPECT_NE(error.find("the " + compression + " " + expected), std::string::npos) << error;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
