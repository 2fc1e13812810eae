// The scan file format on its own: what pcdBytes writes, parsePcd reads back exactly, in both
// encodings; damaged binary_compressed files are named errors, never a crash or a read past the
// end. (That PCL reads our files and we read PCL's is checked in sim/tests/pcd_pcl_test.cpp,
// which may link PCL's io.)
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "common/input_error.hpp"
#include "formats/dataset_format.hpp"
#include "formats/pcd_reader.hpp"

namespace isg::formats {
namespace {

using dataset::PcdData;

// A VLP-16-like turn: ring and time regular, coordinates with noisy mantissas.
std::vector<sensors::ScanPoint> someScan(std::size_t sequences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> metres(-12.0f, 12.0f);
  std::vector<sensors::ScanPoint> points;
  for (std::size_t s = 0; s < sequences; ++s) {
    for (int l = 0; l < 16; ++l) {
      points.push_back({metres(rng), metres(rng), 0.1f * metres(rng), float(int(rng() % 200)),
                        std::uint16_t(l), float(s * 55.296e-6 + l * 2.304e-6)});
    }
  }
  return points;
}

void expectSamePoints(const std::vector<sensors::ScanPoint>& a,
                      const std::vector<sensors::ScanPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
    ASSERT_EQ(a[i].intensity, b[i].intensity) << i;
    ASSERT_EQ(a[i].ring, b[i].ring) << i;
    ASSERT_EQ(a[i].time, b[i].time) << i;
  }
}

std::string pcdErrorOf(const std::string& bytes) {
  try {
    parsePcd(bytes, "s.pcd");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PcdFormat, BothEncodingsReadBackExactly) {
  for (std::size_t sequences : {0u, 1u, 3u, 1808u}) {
    const auto points = someScan(sequences);
    for (PcdData data : {PcdData::kBinary, PcdData::kBinaryCompressed}) {
      const std::string bytes = dataset::pcdBytes(points, data);
      EXPECT_NE(bytes.find(std::string("\nDATA ") + dataset::pcdDataName(data) + "\n"),
                std::string::npos);
      expectSamePoints(parsePcd(bytes, "s.pcd"), points);
    }
  }
}

TEST(PcdFormat, CompressedIsSmallerAndSaysItsSizes) {
  const auto points = someScan(1808);
  const std::string binary = dataset::pcdBytes(points, PcdData::kBinary);
  const std::string compressed = dataset::pcdBytes(points, PcdData::kBinaryCompressed);
  const std::size_t header = compressed.find("DATA binary_compressed\n") + 23;
  std::uint32_t sizes[2];
  std::memcpy(sizes, compressed.data() + header, sizeof sizes);
  EXPECT_EQ(sizes[1], points.size() * 22);  // x y z intensity ring time: 4+4+4+4+2+4 bytes
  EXPECT_EQ(sizes[0], compressed.size() - header - 8);
  // Ring and intensity shrink to little; the noisy x, y, z and time stay as literal runs,
  // 33 bytes for 32: 16 · 28 932 · (12·33/32 + 4·33/32) bytes at most for those four fields.
  EXPECT_LT(compressed.size(), binary.size() * 0.85);
  EXPECT_GT(compressed.size(), binary.size() * 0.6);
}

TEST(PcdFormat, DamagedCompressedDataIsNamed) {
  const auto points = someScan(4);  // 64 points, 1408 bytes unpacked
  const std::string good = dataset::pcdBytes(points, PcdData::kBinaryCompressed);
  const std::size_t header = good.find("DATA binary_compressed\n") + 23;
  auto with_sizes = [&](std::uint32_t compressed, std::uint32_t raw) {
    std::string bytes = good;
    const std::uint32_t sizes[2] = {compressed, raw};
    std::memcpy(bytes.data() + header, sizes, sizeof sizes);
    return bytes;
  };
  std::uint32_t sizes[2];
  std::memcpy(sizes, good.data() + header, sizeof sizes);

  EXPECT_EQ(pcdErrorOf(good.substr(0, header + 5)),
            "s.pcd: data: binary_compressed needs 8 bytes of sizes, the file holds 5");
  EXPECT_EQ(pcdErrorOf(good.substr(0, good.size() - 10)),
            "s.pcd: data: " + std::to_string(sizes[0]) +
                " compressed bytes announced, the file holds " + std::to_string(sizes[0] - 10));
  EXPECT_EQ(pcdErrorOf(with_sizes(sizes[0], 1400)),
            "s.pcd: data: 64 points need 1408 bytes, the file unpacks to 1400");
  // Fewer compressed bytes than written: the stream ends inside a token or short of 1408 bytes.
  EXPECT_EQ(
      pcdErrorOf(with_sizes(sizes[0] / 2, 1408)).rfind("s.pcd: data: the LZF data is damaged", 0),
      0u);
  // A back reference before the start of the output (control byte 0xe0: length 7+, offset
  // from the next byte) is refused by LZF, not followed.
  std::string reference = good;
  reference[header + 8] = char(0xff);
  reference[header + 9] = char(0xff);
  reference[header + 10] = char(0xff);
  EXPECT_EQ(pcdErrorOf(reference).rfind("s.pcd: data: the LZF data is damaged", 0), 0u);
  // A point count whose unpacked size would be absurd is refused before any allocation.
  std::string huge = good;
  const std::string width = "WIDTH 64\n", points_line = "POINTS 64\n";
  huge.replace(huge.find(width), width.size(), "WIDTH 900000000\n");
  huge.replace(huge.find(points_line), points_line.size(), "POINTS 900000000\n");
  EXPECT_EQ(pcdErrorOf(huge).rfind("s.pcd: data: 900000000 points need", 0), 0u);
}

}  // namespace
}  // namespace isg::formats
