// The loop's scan source and the scans it makes: turns made in parts or whole, ahead or on
// demand, by one thread or three, are the same bits; scans the localizer skips change nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "sim/fast_random.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

bool samePoints(const std::vector<LidarPoint>& a, const std::vector<LidarPoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].z != b[i].z ||
        a[i].intensity != b[i].intensity || a[i].ring != b[i].ring || a[i].time != b[i].time) {
      return false;
    }
  }
  return true;
}

TEST(FastRandom, SeedsGiveTheirOwnSequences) {
  Xoshiro256 a(1), b(1), c(2);
  for (int i = 0; i < 100; ++i) {
    const auto x = a();
    EXPECT_EQ(x, b());
    EXPECT_NE(x, c());
  }
  // Uniform draws in [0, 1) with the right mean and spread.
  Xoshiro256 g(deriveSeed(7, 3, 11));
  double sum = 0.0, sum2 = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = g.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 0.002);
  EXPECT_NE(deriveSeed(7, 3, 11), deriveSeed(7, 11, 3));
}

TEST(LidarSimulator, ATurnMadeInPartsIsTheWholeTurn) {
  const Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  const auto lidar = sim.makeLidar();
  const LidarScan whole = sim.scan(40, *lidar);
  EXPECT_GT(whole.timing.casting_s, 0.0);
  EXPECT_GT(whole.timing.noise_s, 0.0);
  const int blocks = lidar->blockCount();
  EXPECT_EQ(blocks, 29);  // 1808 sequences in blocks of 64
  LidarScan joined;
  for (const auto& [first, last] : {std::pair{0, 5}, {5, 6}, {6, 20}, {20, blocks}}) {
    const LidarScan part = sim.scanBlocks(40, *sim.makeLidar(), first, last);
    joined.points.insert(joined.points.end(), part.points.begin(), part.points.end());
    joined.rays += part.rays;
  }
  EXPECT_EQ(joined.rays, whole.rays);
  EXPECT_TRUE(samePoints(joined.points, whole.points));
}

TEST(LookaheadScans, ScansAreTheSameAheadOrOnDemandOnAnyNumberOfThreads) {
  const Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d2.asbuilt", nullptr));
  const auto lidar = sim.makeLidar();
  // Read the first eight (the source starts making scans ahead), then one in four.
  std::vector<bool> read;
  for (int k = 0; k < 24; ++k) read.push_back(k < 8 || k % 4 == 0);
  for (int workers : {0, 1, 2}) {
    SCOPED_TRACE(workers);
    LookaheadScans source(sim, int(read.size()), workers, 4);
    for (int k = 0; k < int(read.size()); ++k) {
      if (!read[k]) {
        source.skip(k);
        continue;
      }
      const sensors::Scan scan = source.scan(k);
      ASSERT_TRUE(samePoints(scan.points, sim.scan(k, *lidar).points)) << k;
    }
    EXPECT_GT(source.stageTimes().seconds("casting"), 0.0);
    // Every scan read was made once; with workers, some made ahead and skipped too.
    if (workers == 0) {
      EXPECT_EQ(source.scansMade(), 12);
    }
    EXPECT_GE(source.scansMade(), 12);
  }
}

// A localizer that reads one scan in three and remembers what it read.
class EveryThirdScan : public slam::Localizer {
 public:
  std::string name() const override { return "every-third"; }
  void pushOdometry(const sensors::Odometry& o) override { latest_ = o; }
  void pushScan(const sensors::Scan& scan) override {
    if (!wantsScan(scan.stamp)) return;
    sizes.push_back(scan.points.size());
  }
  bool wantsScan(double stamp) const override { return int(std::lround(stamp * 10)) % 3 == 0; }
  std::optional<sensors::Odometry> poseInMap() const override { return latest_; }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return std::nullopt; }
  nlohmann::json graph() const override { return {}; }
  std::vector<std::size_t> sizes;

 private:
  std::optional<sensors::Odometry> latest_;
};

TEST(Driver, ScansTheLocalizerSkipsAreNeverMadeAndChangeNothing) {
  const Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d2.asbuilt", nullptr));
  sensors::SensorStreams streams = sensorStreams(sim, 2.0);
  const int total = int(streams.scan_stamps.size());
  EveryThirdScan skipping;
  LookaheadScans source(sim, total, 1);
  const run::RunRecord record = run::runLocalizer({}, skipping, streams, source);
  EXPECT_EQ(record.scans, total);
  EXPECT_EQ(record.scans_read, (total + 2) / 3);
  EXPECT_EQ(int(skipping.sizes.size()), record.scans_read);
  EXPECT_LE(source.scansMade(), record.scans_read + 2);  // at most a few made ahead
  // Fed every scan instead, the localizer says the same after each one.
  EveryThirdScan fed;
  run::LocalizerDriver driver(fed, streams.odometry, streams.scan_period);
  const auto lidar = sim.makeLidar();
  for (int k = 0; k < total; ++k) {
    const LidarScan scan = sim.scan(k, *lidar);
    driver.feed({streams.scan_stamps[k], scan.points});
  }
  EXPECT_EQ(fed.sizes, skipping.sizes);
  ASSERT_EQ(driver.estimateMap().size(), record.estimate_map.size());
  for (std::size_t i = 0; i < record.estimate_map.size(); ++i) {
    EXPECT_EQ(driver.estimateMap()[i].t, record.estimate_map[i].t);
  }
}

}  // namespace
}  // namespace isg::sim
