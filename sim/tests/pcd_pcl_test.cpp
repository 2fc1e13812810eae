// Our scan files against PCL, the reader every other SLAM stack uses: PCL reads both of our
// encodings to the very bytes of the simulated scan, and our reader reads what PCL writes.
#include <gtest/gtest.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "formats/dataset_format.hpp"
#include "formats/pcd_reader.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

namespace fs = std::filesystem;
using formats::dataset::PcdData;

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The points of a PCLPointCloud2 with our layout (point step 22: x y z intensity ring time).
std::vector<sensors::ScanPoint> pointsOf(const pcl::PCLPointCloud2& cloud) {
  std::vector<sensors::ScanPoint> out(cloud.width * cloud.height);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto* at = cloud.data.data() + i * cloud.point_step;
    std::memcpy(&out[i].x, at, 4);
    std::memcpy(&out[i].y, at + 4, 4);
    std::memcpy(&out[i].z, at + 8, 4);
    std::memcpy(&out[i].intensity, at + 12, 4);
    std::memcpy(&out[i].ring, at + 16, 2);
    std::memcpy(&out[i].time, at + 18, 4);
  }
  return out;
}

void expectSame(const std::vector<sensors::ScanPoint>& a,
                const std::vector<sensors::ScanPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a[i].x, &b[i].x, 16), 0) << i;  // x y z intensity, bit for bit
    ASSERT_EQ(a[i].ring, b[i].ring) << i;
    ASSERT_EQ(a[i].time, b[i].time) << i;
  }
}

TEST(PcdWithPcl, PclReadsOurScansAndWeReadPcls) {
  const fs::path dir = fs::temp_directory_path() / "isg_pcd_pcl_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  const LidarScan scan = sim.scan(5);
  ASSERT_GT(scan.points.size(), 20000u);
  for (PcdData data : {PcdData::kBinary, PcdData::kBinaryCompressed}) {
    const fs::path ours = dir / (std::string(formats::dataset::pcdDataName(data)) + ".pcd");
    write(ours, formats::dataset::pcdBytes(scan.points, data));
    pcl::PCLPointCloud2 cloud;
    ASSERT_EQ(pcl::io::loadPCDFile(ours.string(), cloud), 0) << ours;
    ASSERT_EQ(cloud.point_step, 22u);
    std::string fields;
    for (const auto& f : cloud.fields) fields += f.name + " ";
    EXPECT_EQ(fields, "x y z intensity ring time ");
    expectSame(pointsOf(cloud), scan.points);
    expectSame(formats::readPcd(ours.string()), scan.points);

    // PCL's own binary_compressed writer, read back by ours.
    const fs::path theirs = dir / "pcl.pcd";
    ASSERT_EQ(pcl::PCDWriter().writeBinaryCompressed(theirs.string(), cloud), 0);
    expectSame(formats::readPcd(theirs.string()), scan.points);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::sim
