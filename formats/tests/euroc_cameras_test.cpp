// A dataset's EuRoC camera folders read back for the bag exports: calibration, mounts, frames on
// the dataset's clock, JPEG frames, and each bad file named with what is wrong.
#include <gtest/gtest.h>
#include <png.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

#include "common/input_error.hpp"
#include "formats/euroc_cameras.hpp"
#include "formats/jpeg_frame.hpp"
#include "formats/tests/scratch_files.hpp"

namespace isg::formats {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 8, kHeight = 6;

void writePng(const fs::path& path, bool depth) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = kWidth;
  image.height = kHeight;
  image.format = depth ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i * 7);
  ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, pixels.data(), 0, nullptr));
}

const char* kSensorYaml =
    "sensor_type: camera\n"
    "T_BS:\n  cols: 4\n  rows: 4\n"
    "  data: [0, 0, 1, 0.35, -1, 0, 0, 0.02, 0, -1, 0, 0.1, 0, 0, 0, 1]\n"
    "rate_hz: 30\nresolution: [8, 6]\ncamera_model: pinhole\n"
    "intrinsics: [4.5, 4.25, 3.5, 2.5]\n";

// mav0 with cam0 (equidistant) and depth0, two frames each; EuRoC stamps 7 s ahead of the
// simulation's clock.
fs::path writeMav0(const std::string& name) {
  const fs::path dataset = test_files::scratchFolder(name);
  for (const char* camera : {"cam0", "depth0"}) {
    const bool depth = camera[0] == 'd';
    const fs::path folder = dataset / "mav0" / camera;
    fs::create_directories(folder / "data");
    std::ofstream(folder / "sensor.yaml")
        << kSensorYaml
        << (depth ? "distortion_model: radial-tangential\n"
                    "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]\ndepth_scale_m: 0.001\n"
                  : "distortion_model: equidistant\n"
                    "distortion_coefficients: [0.1, -0.02, 0.003, -0.0004]\n");
    std::ofstream csv(folder / "data.csv");
    csv << "#timestamp [ns],filename\n";
    for (const char* stamp : {"7500000000", "7533333333"}) {
      csv << stamp << ',' << stamp << ".png\n";
      writePng(folder / "data" / (std::string(stamp) + ".png"), depth);
    }
  }
  // The dataset's IMU starts at 0 s (the readers are given it): its EuRoC stamp says 7 s.
  fs::create_directories(dataset / "mav0" / "imu0");
  std::ofstream(dataset / "mav0" / "imu0" / "sensor.yaml") << "sensor_type: imu\nrate_hz: 200\n";
  std::ofstream(dataset / "mav0" / "imu0" / "data.csv")
      << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
         "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n"
      << "7000000000,0,0,0,0,0,9.81\n7005000000,0,0,0,0,0,9.81\n";
  return dataset;
}

// The message of the InputError `call` throws, or "no error".
std::string inputErrorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string errorOf(const fs::path& dataset) {
  return inputErrorOf([&] { readEurocCameras(dataset.string(), 0.0); });
}

TEST(EurocCameras, ReadsCalibrationMountsAndFramesOnTheDatasetClock) {
  const fs::path dataset = writeMav0("euroc_cameras");
  const std::vector<EurocCamera> cameras = readEurocCameras(dataset.string(), 0.0);
  ASSERT_EQ(cameras.size(), 2u);  // imu0 is not a camera
  const EurocCamera& cam0 = cameras[0];
  const EurocCamera& depth0 = cameras[1];
  EXPECT_EQ(cam0.name, "cam0");
  EXPECT_FALSE(cam0.depth);
  EXPECT_EQ(depth0.name, "depth0");
  EXPECT_TRUE(depth0.depth);
  EXPECT_EQ(cam0.rate_hz, 30.0);
  EXPECT_EQ(cam0.I_T_C.translation(), Eigen::Vector3d(0.35, 0.02, 0.1));
  EXPECT_EQ(cam0.I_T_C.linear().col(2), Eigen::Vector3d(1, 0, 0));  // optical axis ahead
  const CameraCalibration& k = cam0.calibration;
  EXPECT_EQ(k.width, 8);
  EXPECT_EQ(k.height, 6);
  EXPECT_EQ(k.distortion_model, "equidistant");
  EXPECT_EQ(k.distortion, (std::vector<double>{0.1, -0.02, 0.003, -0.0004}));
  EXPECT_EQ(k.K(), (std::array<double, 9>{4.5, 0, 3.5, 0, 4.25, 2.5, 0, 0, 1}));
  EXPECT_EQ(k.P(), (std::array<double, 12>{4.5, 0, 3.5, 0, 0, 4.25, 2.5, 0, 0, 0, 1, 0}));
  // EuRoC's radial-tangential k1 k2 p1 p2 become ROS's plumb_bob with k3 = 0.
  EXPECT_EQ(depth0.calibration.distortion_model, "plumb_bob");
  EXPECT_EQ(depth0.calibration.distortion.size(), 5u);
  // The 7 s offset found from imu0 comes off every camera's stamps, depth0's too.
  for (const EurocCamera& camera : cameras) {
    ASSERT_EQ(camera.frames.size(), 2u);
    EXPECT_EQ(camera.frames[0].stamp_ns, 7500000000);
    EXPECT_DOUBLE_EQ(camera.frames[0].t, 0.5);
    EXPECT_DOUBLE_EQ(camera.frames[1].t, 0.533333333);
    EXPECT_EQ(camera.frames[1].path,
              (dataset / "mav0" / camera.name / "data" / "7533333333.png").string());
  }
}

TEST(EurocCameras, NoMav0FolderIsNoCamera) {
  EXPECT_TRUE(readEurocCameras(test_files::scratchFolder("euroc_none").string(), 0.0).empty());
}

TEST(EurocCameras, BadFilesAreNamedWithWhatIsWrong) {
  fs::path dataset = writeMav0("euroc_bad");
  const fs::path mav0 = dataset / "mav0";
  fs::remove(mav0 / "cam0" / "data" / "7533333333.png");
  EXPECT_EQ(errorOf(dataset), (mav0 / "cam0" / "data.csv").string() + ": line 3: its image " +
                                  (mav0 / "cam0" / "data" / "7533333333.png").string() +
                                  " is missing");

  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "cam0" / "data.csv", std::ios::app) << "7533333333,7500000000.png\n";
  EXPECT_EQ(errorOf(dataset),
            (mav0 / "cam0" / "data.csv").string() + ": line 4: stamps do not increase");

  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "depth0" / "data.csv", std::ios::app) << "7600000000;x.png\n";
  EXPECT_EQ(errorOf(dataset), (mav0 / "depth0" / "data.csv").string() +
                                  ": line 4: not \"<timestamp ns>,<file name>\"");

  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "cam0" / "data.csv", std::ios::app) << "7600000000,../x.png\n";
  EXPECT_EQ(errorOf(dataset),
            (mav0 / "cam0" / "data.csv").string() + ": line 4: \"../x.png\" is not a file name");

  dataset = writeMav0("euroc_bad");
  fs::remove(mav0 / "imu0" / "data.csv");
  EXPECT_EQ(errorOf(dataset), (mav0 / "imu0" / "data.csv").string() +
                                  ": cannot be read: it ties the cameras' stamps to the "
                                  "dataset's clock");

  // An IMU 2 ms off a whole second from the dataset's: not the same run.
  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "imu0" / "data.csv") << "#timestamp [ns],...\n7002000000,0,0,0,0,0,9.81\n";
  EXPECT_EQ(errorOf(dataset), (mav0 / "imu0" / "data.csv").string() +
                                  ": line 2: its first stamp is not the dataset's first IMU time "
                                  "(0.000000 s) plus whole seconds: is mav0 from another run?");

  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "cam0" / "sensor.yaml")
      << kSensorYaml << "distortion_model: fov\ndistortion_coefficients: [0.9]\n";
  EXPECT_EQ(errorOf(dataset), (mav0 / "cam0" / "sensor.yaml").string() +
                                  ": /distortion_model: \"fov\" is not equidistant or "
                                  "radial-tangential");

  dataset = writeMav0("euroc_bad");
  std::ofstream(mav0 / "cam0" / "sensor.yaml")
      << "sensor_type: camera\nrate_hz: 30\nT_BS:\n  data: [1, 0, 0, 1]\n";
  EXPECT_EQ(errorOf(dataset),
            (mav0 / "cam0" / "sensor.yaml").string() + ": /T_BS/data: has 4 numbers, expected 16");

  dataset = writeMav0("euroc_bad");
  fs::remove_all(mav0 / "cam0");
  EXPECT_EQ(errorOf(dataset),
            mav0.string() + ": has depth images but no camera they are registered to");
}

TEST(JpegFrame, EncodesAnRgbPngAndRefusesOtherFiles) {
  const fs::path dir = test_files::scratchFolder("jpeg_frame");
  writePng(dir / "rgb.png", false);
  const std::string jpeg = rgbPngFileToJpeg((dir / "rgb.png").string(), kWidth, kHeight);
  ASSERT_GT(jpeg.size(), 4u);
  EXPECT_EQ(jpeg.substr(0, 2), "\xff\xd8");             // start of image
  EXPECT_EQ(jpeg.substr(jpeg.size() - 2), "\xff\xd9");  // end of image
  // A frame's width and height in its SOF0 marker (baseline): 6 rows of 8.
  const std::size_t sof = jpeg.find("\xff\xc0");
  ASSERT_NE(sof, std::string::npos);
  EXPECT_EQ(jpeg.substr(sof + 5, 4), std::string("\x00\x06\x00\x08", 4));

  auto errorFor = [](const fs::path& path, int width = kWidth) {
    return inputErrorOf([&] { rgbPngFileToJpeg(path.string(), width, kHeight); });
  };
  EXPECT_EQ(errorFor(dir / "rgb.png", 9),
            (dir / "rgb.png").string() + ": is 8 x 6 pixels, its camera 9 x 6");
  writePng(dir / "depth.png", true);
  EXPECT_EQ(errorFor(dir / "depth.png"), (dir / "depth.png").string() + ": not an 8-bit RGB image");
  std::ofstream(dir / "text.png") << "not a picture";
  EXPECT_EQ(
      errorFor(dir / "text.png").rfind((dir / "text.png").string() + ": not a PNG image: ", 0), 0u);
}

// A depth frame goes into a bag as its PNG bytes, once they are seen to be a 16-bit grey PNG of
// the camera's size.
TEST(EurocCameras, ADepthFrameIsCarriedAsItsPngOnceChecked) {
  const fs::path dir = test_files::scratchFolder("depth_png");
  writePng(dir / "depth.png", true);
  writePng(dir / "rgb.png", false);
  std::ofstream(dir / "text.png") << "not a picture at all, but long enough to hold a header";
  EXPECT_EQ(readDepthPng((dir / "depth.png").string(), kWidth, kHeight),
            test_files::slurp(dir / "depth.png"));
  auto errorFor = [](const fs::path& path, int width) {
    return inputErrorOf([&] { readDepthPng(path.string(), width, kHeight); });
  };
  EXPECT_EQ(errorFor(dir / "depth.png", 640),
            (dir / "depth.png").string() + ": is 8 x 6 pixels, its camera 640 x 6");
  EXPECT_EQ(errorFor(dir / "rgb.png", kWidth),
            (dir / "rgb.png").string() + ": not a 16-bit grey depth image");
  EXPECT_EQ(errorFor(dir / "text.png", kWidth)
                .rfind((dir / "text.png").string() + ": not a PNG image: ", 0),
            0u);
  EXPECT_EQ(errorFor(dir / "missing.png", kWidth),
            (dir / "missing.png").string() + ": cannot open file: No such file or directory");
}

}  // namespace
}  // namespace isg::formats
