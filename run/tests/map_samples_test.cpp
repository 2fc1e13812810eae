// The run's map sample: one scan a second, thinned to every 8th point, and bounded on long runs
// by keeping every other scan and doubling the spacing.
#include "run/map_samples.hpp"

#include <gtest/gtest.h>

namespace isg::run {
namespace {

// A scan of 80 points at `stamp`, the first point's x the stamp (to tell the scans apart).
sensors::Scan scanAt(double stamp) {
  sensors::Scan scan;
  scan.stamp = stamp;
  for (int i = 0; i < 80; ++i) {
    scan.points.push_back(
        {float(stamp), float(i), 1.0f, 0.0f, 0, 0.001f * float(i)});  // x y z i ring t
  }
  return scan;
}

TEST(MapSamples, OneScanASecondThinnedToEveryEighthPoint) {
  RunRecord record;
  for (int k = 0; k < 50; ++k) offerMapSample(record, scanAt(0.1 * k));  // 5 s of 10 Hz scans
  ASSERT_EQ(record.map_samples.size(), 5u);                              // 0, 1, 2, 3, 4 s
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(record.map_samples[i].stamp, double(i), 1e-9);
  const auto& points = record.map_samples[1].points;
  ASSERT_EQ(points.size(), 10u);  // 80 / 8
  EXPECT_FLOAT_EQ(points[1][1], 8.0f);
  EXPECT_FLOAT_EQ(points[1][3], 0.008f);
  EXPECT_EQ(record.map_sample_seconds, 1.0);
}

TEST(MapSamples, ALongRunKeepsEveryOtherScanAndDoublesTheSpacing) {
  RunRecord record;
  // 3000 s of scans at 10 Hz: 256 kept at 1 s (0 … 255 s), then at 256 s every other one
  // goes (128 left, 2 s apart, the last at 254 s) and 256 s is kept; the spacing doubles
  // again each time 256 are kept: at 512 s (to 4 s), 1024 s (8 s) and 2048 s (16 s).
  ASSERT_EQ(kMaxMapSamples, 256u);
  for (int k = 0; k < 30000; ++k) offerMapSample(record, scanAt(0.1 * k));
  const auto& samples = record.map_samples;
  EXPECT_EQ(record.map_sample_seconds, 16.0);
  ASSERT_LE(samples.size(), kMaxMapSamples);
  EXPECT_EQ(samples.size(), 188u);  // 0, 16, …, 2992 s
  // Evenly spread over the whole run: 16 s apart from the start, the last within 16 s of the end.
  for (std::size_t i = 0; i < samples.size(); ++i) {
    EXPECT_NEAR(samples[i].stamp, 16.0 * double(i), 1e-6) << i;
    // Each kept scan keeps its own points, the first one too.
    ASSERT_EQ(samples[i].points.size(), 10u) << i;
    EXPECT_NEAR(samples[i].points[0][0], samples[i].stamp, 1e-3) << i;
  }
  EXPECT_GT(samples.back().stamp, 2999.9 - 16.0);
}

}  // namespace
}  // namespace isg::run
