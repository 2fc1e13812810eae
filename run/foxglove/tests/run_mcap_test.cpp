#include "run/foxglove/run_mcap.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "common/input_error.hpp"
#include "formats/foxglove_json.hpp"
#include "run/foxglove/growing_path.hpp"
#include "run/foxglove/live_run_mcap.hpp"

namespace isg::run {
namespace {

namespace fs = std::filesystem;

class RunMcapWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("isg_run_mcap_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::map<std::string, std::uint64_t> byTopic(const RunMcapWriter& writer) {
  std::map<std::string, std::uint64_t> counts;
  for (const auto& [topic, n] : writer.counts()) counts[topic] = n;
  return counts;
}

TEST_F(RunMcapWriterTest, SnapshotsComeOncePerPeriodAndTheFileOnlyAtTheEnd) {
  const fs::path path = dir_ / "run.mcap";
  RunMcapOptions options;
  options.snapshot_period = 1.0;
  common::Trajectory truth = {{0.0, Eigen::Isometry3d::Identity()},
                              {1.0, Eigen::Isometry3d(Eigen::Translation3d(1, 0, 0))}};
  RunMcapWriter writer(path.string(), options, nullptr, Eigen::Isometry3d::Identity(), truth);
  const nlohmann::json graph = {{"keyframes", nlohmann::json::array()}};
  // Moments every 0.4 s; a map placed in the plan from 0.8 s on.
  for (int k = 0; k <= 6; ++k) {
    const double stamp = 0.4 * k;
    RunMoment moment;
    moment.stamp = stamp;
    moment.M_T_R = Eigen::Isometry3d(Eigen::Translation3d(stamp, 0, 0));
    if (k >= 2) moment.B_T_M = Eigen::Isometry3d::Identity();
    // Due at 0, then at the first moment 1 s after the last snapshot: 1.2, 2.4.
    const bool due = writer.snapshotDue(stamp);
    EXPECT_EQ(due, k == 0 || k == 3 || k == 6) << stamp;
    if (due) moment.graph = &graph;
    if (k == 1) moment.events.push_back({0.4, 1, "matched", "hand"});
    writer.add(moment);
  }
  EXPECT_FALSE(fs::exists(path));  // nothing before finish()
  writer.finish(graph, nullptr);
  EXPECT_TRUE(fs::exists(path));
  const auto counts = byTopic(writer);
  EXPECT_EQ(counts.count("/plan"), 0u);  // no plan given
  // base_link -> velodyne once, map -> base_link 7 times, plan -> map 5 times.
  EXPECT_EQ(counts.at("/tf"), 1u + 7u + 5u);
  EXPECT_EQ(counts.at("/sgraph"), 3u + 1u);  // three snapshots and the final graph
  EXPECT_EQ(counts.at("/estimate/path"), 4u);
  EXPECT_EQ(counts.at("/groundtruth/path"), 1u);
  EXPECT_EQ(counts.at("/isg/log"), 1u);
  EXPECT_EQ(counts.at("/isg/matching"), 0u);  // the graph has no matcher
  EXPECT_EQ(counts.at("/velodyne_points"), 0u);
}

// A foxglove.PosesInFrame built whole, as nlohmann::json writes it: what GrowingPath's text must
// be.
std::string posesInFrame(formats::RosTime stamp, const std::string& frame,
                         const std::vector<Eigen::Isometry3d>& poses) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& T : poses) list.push_back(formats::foxglove::pose(T));
  return nlohmann::json{
      {"timestamp", formats::foxglove::time(stamp)}, {"frame_id", frame}, {"poses", list}}
      .dump();
}

TEST(GrowingPath, KeepsAPoseEverySpacingAndTheLatestAsPosesInFrameWritesThem) {
  GrowingPath path(0.1);
  EXPECT_TRUE(path.empty());
  const auto at = [](double x) { return Eigen::Isometry3d(Eigen::Translation3d(x, 0, 0)); };
  // 0 kept; 0.05 not (5 cm from 0); 0.12 kept; 0.2 not (8 cm from 0.12), but the latest.
  for (double x : {0.0, 0.05, 0.12, 0.2}) path.add(at(x));
  EXPECT_EQ(path.size(), 3);
  const formats::RosTime stamp{1000000002, 5};
  EXPECT_EQ(path.message(stamp, "plan"), posesInFrame(stamp, "plan", {at(0.0), at(0.12), at(0.2)}));
  path.add(at(0.25));  // 13 cm from 0.12: kept, and the latest
  EXPECT_EQ(path.size(), 3);
  EXPECT_EQ(path.message(stamp, "map"), posesInFrame(stamp, "map", {at(0.0), at(0.12), at(0.25)}));
}

TEST_F(RunMcapWriterTest, ALiveFileLeftWithoutFinishLeavesNothing) {
  // The run failed (an exception, Ctrl-C) after the file was opened: its thread stops, and
  // neither the file nor a temporary one is left.
  const fs::path path = dir_ / "live.mcap";
  {
    sensors::SensorStreams streams;
    streams.ground_truth = {{0.0, Eigen::Isometry3d::Identity()}};
    LiveRunMcap live(path.string(), RunMcapOptions{}, RunSetup{}, streams);
  }
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RunMcapWriterTest, ARunFolderThatIsNotOneIsSaidSo) {
  EXPECT_FALSE(isRunFolder(dir_.string()));
  // Its files there, but a metrics.json that isg did not write: said so, and nothing written.
  const auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  };
  write("metrics.json", R"({"matching_events": [{"stamp": "soon"}]})");
  write("sgraph.json", "{}");
  write("estimate_map.tum", "0.1 0 0 0 0 0 0 1\n");
  write("estimate.tum", "");
  ASSERT_TRUE(isRunFolder(dir_.string()));
  try {
    exportRunMcap(dir_.string(), (dir_ / "x.mcap").string(), {});
    ADD_FAILURE() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not as isg writes it"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.mcap"));
  for (const char* name : {"metrics.json", "sgraph.json", "estimate_map.tum", "estimate.tum"}) {
    fs::remove(dir_ / name);
  }
  EXPECT_THROW(exportRunMcap(dir_.string(), (dir_ / "x.mcap").string(), {}), common::InputError);
  EXPECT_FALSE(fs::exists(dir_ / "x.mcap"));
}

}  // namespace
}  // namespace isg::run
