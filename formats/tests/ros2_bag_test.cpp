#include "formats/ros2_bag.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;

const fs::path kIndoorRos2Bag =
    fs::path(ISG_SOURCE_DIR) / "formats/tests/data/vlp16-real/nebula-vlp16-indoor.db3";

// A rosbag2 folder as `ros2 bag record` leaves it: the database under another name and the
// metadata.yaml naming it, with `info` as its rosbag2_bagfile_information's last lines.
fs::path bagFolder(const std::string& test, const std::string& info) {
  const fs::path dir = test_files::scratchFolder(test);
  fs::copy_file(kIndoorRos2Bag, dir / "run_0.db3");
  std::ofstream(dir / "metadata.yaml") << "rosbag2_bagfile_information:\n"
                                          "  version: 5\n"
                                          "  message_count: 4\n"
                                       << info;
  return dir;
}

std::string ros2BagErrorOf(const fs::path& dir) {
  try {
    Ros2Bag bag(dir.string());
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(read)";
}

TEST(Ros2Bag, AFolderIsReadAsItsMetadataNamesItsFiles) {
  const fs::path dir = bagFolder("ros2_bag_metadata",
                                 "  storage_identifier: sqlite3\n"
                                 "  compression_format: \"\"\n"
                                 "  compression_mode: \"\"\n"
                                 "  relative_file_paths:\n"
                                 "    - run_0.db3\n");
  // A stray database beside it is not part of the bag.
  fs::copy_file(kIndoorRos2Bag, dir / "old.db3");
  const Ros2Bag bag(dir.string());
  ASSERT_EQ(bag.topics().size(), 1u);
  EXPECT_EQ(bag.topics()[0].name, "/velodyne_packets");
  EXPECT_EQ(bag.topics()[0].messages, 4u);
  EXPECT_EQ(bag.messages("/velodyne_packets").size(), 4u);
  fs::remove_all(dir);
}

// Two files of one split bag (the same four scans twice): read() merges them in stamp order,
// ties in the files' order, one message at a time, as messages() gives them.
TEST(Ros2Bag, ASplitBagIsReadInStampOrderAcrossItsFiles) {
  const fs::path dir = bagFolder("ros2_bag_split_read",
                                 "  storage_identifier: sqlite3\n"
                                 "  relative_file_paths: [run_0.db3, run_1.db3]\n");
  fs::copy_file(kIndoorRos2Bag, dir / "run_1.db3");
  const Ros2Bag bag(dir.string());
  EXPECT_EQ(bag.topics()[0].messages, 8u);
  const std::vector<Ros2Message> listed = bag.messages("/velodyne_packets");
  std::vector<std::int64_t> stamps;
  std::uint64_t expected_index = 0;
  bag.read({}, [&](const Ros2MessageView& m) {
    EXPECT_EQ(m.topic->name, "/velodyne_packets");
    EXPECT_EQ(m.index, expected_index++);
    EXPECT_EQ(m.data, listed[stamps.size()].data);
    stamps.push_back(m.stamp_ns);
    return true;
  });
  ASSERT_EQ(stamps.size(), 8u);
  EXPECT_EQ(stamps[0], stamps[1]);  // each scan from both files, one after the other
  EXPECT_EQ(stamps[7], 1673400472138016708);
  EXPECT_TRUE(std::is_sorted(stamps.begin(), stamps.end()));
  int seen = 0;
  bag.read({"/velodyne_packets"}, [&](const Ros2MessageView&) { return ++seen < 3; });
  EXPECT_EQ(seen, 3);  // stopped when asked
  try {
    bag.read({"/points"}, [](const Ros2MessageView&) { return true; });
    ADD_FAILURE() << "an unknown topic was read";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.string() + ": no topic /points (the bag has: /velodyne_packets)");
  }
  fs::remove_all(dir);
}

TEST(Ros2Bag, WhatItCannotReadIsSaid) {
  const auto refused = [](const std::string& test, const std::string& info) {
    const fs::path dir = bagFolder(test, info);
    std::string error = ros2BagErrorOf(dir);
    const std::string prefix = (dir / "metadata.yaml").string() + ": ";
    if (error.rfind(prefix, 0) == 0) error = error.substr(prefix.size());
    fs::remove_all(dir);
    return error;
  };
  EXPECT_EQ(
      refused("ros2_bag_mcap", "  storage_identifier: mcap\n  relative_file_paths: [a.mcap]\n"),
      "relative_file_paths[0] names a.mcap, which is not in the folder");
  EXPECT_EQ(refused("ros2_bag_odd", "  storage_identifier: tape\n"),
            "unknown storage \"tape\" (rosbag2 writes \"sqlite3\" or \"mcap\")");
  EXPECT_EQ(refused("ros2_bag_zstd",
                    "  storage_identifier: sqlite3\n  compression_format: zstd\n"
                    "  compression_mode: FILE\n  relative_file_paths: [run_0.db3.zstd]\n"),
            "a compressed bag (compression_mode FILE, format zstd) is not read; write it "
            "uncompressed (ros2 bag convert)");
  EXPECT_EQ(refused("ros2_bag_split",
                    "  storage_identifier: sqlite3\n"
                    "  relative_file_paths: [run_0.db3, run_1.db3]\n"),
            "relative_file_paths[1] names run_1.db3, which is not in the folder");
  EXPECT_EQ(refused("ros2_bag_nofiles", "  storage_identifier: sqlite3\n"),
            "rosbag2_bagfile_information.relative_file_paths lists no file");
  EXPECT_EQ(refused("ros2_bag_notyaml", "  relative_file_paths: [\n").rfind("not YAML: ", 0), 0u);
  // Some other program's metadata.yaml.
  const fs::path dir = test_files::scratchFolder("ros2_bag_other");
  std::ofstream(dir / "metadata.yaml") << "camera: {fps: 30}\n";
  EXPECT_EQ(ros2BagErrorOf(dir),
            (dir / "metadata.yaml").string() +
                ": no rosbag2_bagfile_information: not a rosbag2 bag's metadata");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
