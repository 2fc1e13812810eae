// The bag 2.0 container on its own: ROS time, records, chunks and the index, and a bag left only
// when closed; cli/tests/rosbag_oracle.py reads a whole exported dataset with Debian's
// python3-rosbag.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "formats/rosbag_writer.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;
using test_files::slurp;

fs::path writerScratch(const std::string& name) {
  return test_files::scratchFolder("rosbag_" + name);
}

// One record of a bag: its header fields and its data.
struct Record {
  std::map<std::string, std::string> fields;
  std::string data;
  std::size_t end = 0;
};
template <typename T>
T as(const std::string& bytes) {
  T value;
  EXPECT_EQ(bytes.size(), sizeof(T));
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}
Record recordAt(const std::string& bag, std::size_t at) {
  Record r;
  const auto header_size = as<std::uint32_t>(bag.substr(at, 4));
  std::size_t p = at + 4;
  while (p < at + 4 + header_size) {
    const auto size = as<std::uint32_t>(bag.substr(p, 4));
    const std::string field = bag.substr(p + 4, size);
    const std::size_t eq = field.find('=');
    r.fields[field.substr(0, eq)] = field.substr(eq + 1);
    p += 4 + size;
  }
  const auto data_size = as<std::uint32_t>(bag.substr(p, 4));
  r.data = bag.substr(p + 4, data_size);
  r.end = p + 4 + data_size;
  return r;
}

TEST(RosTime, FromSecondsRoundsToTheNanosecond) {
  const formats::RosTime t = formats::RosTime::fromSeconds(12.3456789014, 1000000000);
  EXPECT_EQ(t.sec, 1000000012u);
  EXPECT_EQ(t.nsec, 345678901u);
  EXPECT_EQ(formats::RosTime::fromSeconds(0.9999999999).sec, 1u);
  EXPECT_EQ(formats::RosTime::fromSeconds(0.9999999999).nsec, 0u);
  EXPECT_THROW(formats::RosTime::fromSeconds(-1.0), std::invalid_argument);
  EXPECT_THROW(formats::RosTime::fromSeconds(5e9), std::invalid_argument);
  EXPECT_THROW(formats::RosTime::fromSeconds(4e9, 1000000000), std::invalid_argument);
}

TEST(RosbagWriter, WritesTheVersionHeaderChunksAndIndex) {
  const fs::path dir = writerScratch("writer");
  const formats::RosMessageType type{"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1",
                                     "string data\n"};
  {
    formats::RosbagWriter bag((dir / "a.bag").string(), false);
    const int a = bag.connect("/a", type);
    const int b = bag.connect("/b", type, true);
    bag.write(a, formats::RosTime{10, 0}, std::string("\x02\0\0\0hi", 6));
    bag.write(b, formats::RosTime{10, 5}, std::string("\x01\0\0\0x", 5));
    bag.write(a, formats::RosTime{11, 0}, std::string("\x00\0\0\0", 4));
    bag.close();
    EXPECT_EQ(bag.counts(), (std::vector<std::uint64_t>{2, 1}));
  }
  const std::string bytes = slurp(dir / "a.bag");
  ASSERT_EQ(bytes.substr(0, 13), "#ROSBAG V2.0\n");
  const Record header = recordAt(bytes, 13);
  EXPECT_EQ(header.end, 13u + 4096u);  // padded to 4096 bytes
  EXPECT_EQ(as<std::uint8_t>(header.fields.at("op")), 0x03);
  EXPECT_EQ(as<std::uint32_t>(header.fields.at("conn_count")), 2u);
  EXPECT_EQ(as<std::uint32_t>(header.fields.at("chunk_count")), 1u);
  // The chunk: connection records before each connection's first message, then the messages.
  const Record chunk = recordAt(bytes, header.end);
  EXPECT_EQ(as<std::uint8_t>(chunk.fields.at("op")), 0x05);
  EXPECT_EQ(chunk.fields.at("compression"), "none");
  EXPECT_EQ(as<std::uint32_t>(chunk.fields.at("size")), chunk.data.size());
  std::vector<int> ops;
  for (std::size_t at = 0; at < chunk.data.size();) {
    const Record r = recordAt(chunk.data, at);
    ops.push_back(as<std::uint8_t>(r.fields.at("op")));
    at = r.end;
  }
  EXPECT_EQ(ops, (std::vector<int>{7, 2, 7, 2, 2}));
  // Its index: one record per connection, with the messages' offsets in the chunk.
  const Record index_a = recordAt(bytes, chunk.end);
  EXPECT_EQ(as<std::uint8_t>(index_a.fields.at("op")), 0x04);
  EXPECT_EQ(as<std::uint32_t>(index_a.fields.at("count")), 2u);
  const auto offset = as<std::uint32_t>(index_a.data.substr(8, 4));
  const Record first = recordAt(chunk.data, offset);
  EXPECT_EQ(first.data, std::string("\x02\0\0\0hi", 6));
  // The index section the header points at: connections, then the chunk's info.
  const auto index_position = as<std::uint64_t>(header.fields.at("index_pos"));
  const Record connection = recordAt(bytes, std::size_t(index_position));
  EXPECT_EQ(as<std::uint8_t>(connection.fields.at("op")), 0x07);
  EXPECT_EQ(connection.fields.at("topic"), "/a");
  EXPECT_NE(connection.data.find("type=std_msgs/String"), std::string::npos);
  const Record latched = recordAt(bytes, connection.end);
  EXPECT_NE(latched.data.find("latching=1"), std::string::npos);
  const Record info = recordAt(bytes, latched.end);
  EXPECT_EQ(as<std::uint8_t>(info.fields.at("op")), 0x06);
  EXPECT_EQ(as<std::uint64_t>(info.fields.at("chunk_pos")), 13u + 4096u);
  EXPECT_EQ(info.fields.at("end_time").substr(0, 4), std::string("\x0b\0\0\0", 4));
  EXPECT_EQ(info.end, bytes.size());
  fs::remove_all(dir);
}

TEST(RosbagWriter, LeavesNothingUnlessClosedAndKeepsAnExistingBag) {
  const fs::path dir = writerScratch("atomic");
  const std::string path = (dir / "b.bag").string();
  {
    formats::RosbagWriter bag(path, false);
    bag.connect("/a", {"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data\n"});
  }  // destroyed without close(): an error or an interrupt
  EXPECT_TRUE(fs::is_empty(dir));
  std::ofstream(path) << "old";
  try {
    formats::RosbagWriter bag(path, false);
    FAIL() << "an existing bag was not refused";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": already exists (use --force to replace it)");
  }
  // --force replaces only a bag of ours: a file of the user's is never replaced.
  try {
    formats::RosbagWriter bag(path, true);
    FAIL() << "a file isg did not write was replaced";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path +
                  ": not replaced: it is not a ROS bag that isg wrote (--force replaces only "
                  "those); remove it yourself or give another path");
  }
  EXPECT_EQ(slurp(path), "old");
  fs::remove(path);
  formats::RosbagWriter(path, false).close();
  const std::string first = slurp(path);
  EXPECT_NE(first.find(common::kWrittenByIsg),
            std::string::npos);  // the mark, in the header's padding
  formats::RosbagWriter replaced(path, true);
  replaced.connect("/a", {"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data\n"});
  EXPECT_EQ(slurp(path), first);  // until it is closed
  replaced.close();
  EXPECT_EQ(slurp(path).substr(0, 13), "#ROSBAG V2.0\n");
  EXPECT_NE(slurp(path), first);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
