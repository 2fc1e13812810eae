// imu.csv: the reader names the bad line, and the writer's text reads back to the same numbers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "formats/dataset_format.hpp"
#include "formats/imu_file.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;

TEST(ImuFile, ReadsSamplesAndNamesTheBadLine) {
  const fs::path dir = test_files::scratchFolder("imu_file");
  auto write = [&](const std::string& text) {
    std::ofstream(dir / "imu.csv") << text;
    return (dir / "imu.csv").string();
  };
  const std::string path =
      write("t,ax,ay,az,gx,gy,gz\n0.000000,0,0,9.81,0,0,0.5\n0.005,1e-3,2,3,4,5,6\n");
  const auto samples = readImuFile(path);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[1].t, 0.005);
  EXPECT_EQ(samples[1].accelerometer, Eigen::Vector3d(1e-3, 2, 3));
  EXPECT_EQ(samples[0].gyroscope.z(), 0.5);
  auto error = [&](const std::string& text) {
    try {
      readImuFile(write(text));
    } catch (const common::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("t ax ay az gx gy gz\n"),
            path + ": line 1: expected the header \"t,ax,ay,az,gx,gy,gz\"");
  EXPECT_EQ(error("t,ax,ay,az,gx,gy,gz\n0,0,0,9.81,0,0,0\n0.005,1,2,3,4,5\n"),
            path + ": line 3: expected 7 comma-separated numbers (t,ax,ay,az,gx,gy,gz), got 6");
  // Each bad number named by its column, and for what it is.
  const std::string head = "t,ax,ay,az,gx,gy,gz\n";
  EXPECT_EQ(error(head + "0,0,0,9.81,0,0,nan\n"),
            path + ": line 2: column 7 (gz): \"nan\" is not a number");
  EXPECT_EQ(error(head + "0,NaN,0,9.81,0,0,0\n"),
            path + ": line 2: column 2 (ax): \"NaN\" is not a number");
  EXPECT_EQ(error(head + "0,0,0,1e999,0,0,0\n"),
            path + ": line 2: column 4 (az): \"1e999\" is out of range (not a finite double)");
  EXPECT_EQ(error(head + "0,0,-inf,9.81,0,0,0\n"),
            path + ": line 2: column 3 (ay): \"-inf\" is out of range (not a finite double)");
  EXPECT_EQ(error(head + "0,0,0,9.81,x,0,0\n"), path + ": line 2: column 5 (gx): not a number");
  EXPECT_EQ(error(head + "0,0,0,9.81;0,0,0\n"),
            path + ": line 2: column 4 (az): expected a comma after the number");
  EXPECT_EQ(error(head + "0,0,0,9.81,0,0,0,7\n"), path + ": line 2: text after the 7th number");
  EXPECT_EQ(error("t,ax,ay,az,gx,gy,gz\n0.1,0,0,9.81,0,0,0\n0.1,0,0,9.81,0,0,0\n"),
            path + ": line 3: time does not increase");
  // The writer's text reads back to the same numbers (nine significant digits).
  sensors::ImuSample s;
  s.t = 1.25;
  s.accelerometer = Eigen::Vector3d(0.123456789, -9.80665, 1e-7);
  s.gyroscope = Eigen::Vector3d(1, 2, 3);
  const auto back = readImuFile(write(dataset::imuText({s})));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].accelerometer, s.accelerometer);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::formats
