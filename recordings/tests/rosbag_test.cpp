// The export of a dataset as a ROS 1 bag, on its own: a missing dataset is named and nothing is
// written. The bag's container is formats/tests/rosbag_writer_test.cpp's; a whole exported dataset
// read by Debian's python3-rosbag is cli/tests/rosbag_oracle.py's.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/input_error.hpp"
#include "formats/tests/scratch_files.hpp"
#include "recordings/rosbag_export.hpp"

namespace isg::recordings {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return formats::test_files::scratchFolder("rosbag_" + name);
}

TEST(RosbagExport, AMissingDatasetIsAnInputErrorAndWritesNothing) {
  const fs::path dir = scratch("export");
  try {
    exportRosbag((dir / "nothing").string(), (dir / "x.bag").string(), {}, nullptr);
    FAIL() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "nothing").string() + ": not a dataset folder (no such directory)");
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::recordings
