#include "bim/recorded_start_pose.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"

namespace isg::bim {
namespace {

// A table in a file of its own, removed after the test.
class StartPoseTable : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("isg_start_pose_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& text) {
    const std::string path = (dir_ / "init_gt_poses.csv").string();
    std::ofstream(path) << text;
    return path;
  }
  // The reason of the InputError reading `sequence` from `text` throws, or "" when none.
  std::string errorOf(const std::string& text, const std::string& sequence) {
    try {
      readRecordedStartPose(write(text), sequence);
    } catch (const common::InputError& e) {
      return e.reason();
    }
    return "";
  }

  std::filesystem::path dir_;
};

constexpr const char* kHeader = "#Sequence Name,Floor Plan,timestamp,tx,ty,tz,qx,qy,qz,qw\n";

TEST_F(StartPoseTable, TheRowOfTheSequenceIsReadBlanksAroundFieldsAllowed) {
  // The second row as the benchmark's table writes one of its rows: a blank after each comma.
  const std::string path = write(
      std::string(kHeader) +
      "floor_1_run_1,floor_1.png,10005.005009000,36.95,18.60,1.04,0,0,0,1\n"
      "floor_UG1_run_1,floor_UG1.png,10005.005036000, 56.5, 49.75, 1.5, 0, 0, 0.7071067811865476, "
      "0.7071067811865476\r\n");
  const RecordedStartPose row = readRecordedStartPose(path, "floor_UG1_run_1");
  EXPECT_EQ(row.sequence, "floor_UG1_run_1");
  EXPECT_EQ(row.plan_file, "floor_UG1.png");
  EXPECT_EQ(row.line, 3);
  EXPECT_DOUBLE_EQ(row.stamp, 10005.005036);
  EXPECT_DOUBLE_EQ(row.pose.translation().x(), 56.5);
  EXPECT_DOUBLE_EQ(row.pose.translation().y(), 49.75);
  EXPECT_DOUBLE_EQ(row.pose.translation().z(), 1.5);
  // A quarter turn about z: x goes to y.
  const Eigen::Vector3d x = row.pose.linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.x(), 0.0, 1e-12);
  EXPECT_NEAR(x.y(), 1.0, 1e-12);
}

TEST_F(StartPoseTable, ASequenceNotInTheTableIsNamedWithTheOnesThatAre) {
  EXPECT_EQ(
      errorOf(std::string(kHeader) + "a,a.png,1,0,0,0,0,0,0,1\nb,b.png,1,0,0,0,0,0,0,1\n", "c"),
      "no row for sequence \"c\"; the table has a, b");
  EXPECT_EQ(errorOf(kHeader, "c"), "no row for sequence \"c\": the table has no rows");
}

TEST_F(StartPoseTable, ABadRowIsSaidWithItsLine) {
  EXPECT_EQ(errorOf(std::string(kHeader) + "a,a.png,1,0,0,0,0,0,0,1\nb,b.png,1,0,0\n", "a"),
            "line 3: expected 10 fields (sequence, floor plan, timestamp, tx, ty, tz, qx, qy, qz, "
            "qw), found 5");
  EXPECT_EQ(errorOf("a,a.png,1,0,0,zero,0,0,0,1\n", "a"),
            "line 1: tz (\"zero\") is not a finite decimal number");
  EXPECT_EQ(errorOf("a,a.png,1,0,0,0,0,0,0,2\n", "a"),
            "line 1: the quaternion is not of unit length");
  EXPECT_EQ(errorOf("a,a.png,1,0,0,0,0,0,0,1\n\n# again\na,a.png,2,0,0,0,0,0,0,1\n", "a"),
            "line 4: sequence \"a\" is given twice (first on line 1)");
  EXPECT_EQ(errorOf(",a.png,1,0,0,0,0,0,0,1\n", "a"), "line 1: no sequence name");
}

TEST_F(StartPoseTable, AMissingFileIsSaid) {
  try {
    readRecordedStartPose((dir_ / "none.csv").string(), "a");
    FAIL() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), (dir_ / "none.csv").string());
    EXPECT_EQ(e.reason(), "cannot open file");
  }
}

}  // namespace
}  // namespace isg::bim
