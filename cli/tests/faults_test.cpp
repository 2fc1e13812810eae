// Faults and runs that cannot do their job, fed to the real `isg`: damaged dataset files, a full
// disk, a read-only folder, an interrupted command, a route that goes nowhere. Each gets exit 1
// (or 128 + signal) with a message naming the file and where in it, and nothing half-written.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "bim/tests/test_plans.hpp"
#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A short dataset of the first reference world, made once per test in its sandbox.
void makeDataset(const testing::Sandbox& sandbox, const std::string& name = "ds",
                 const std::string& duration = "3") {
  const auto result = sandbox.run("simulate builtin:d1 --duration " + duration + " -q -o " + name);
  ASSERT_EQ(result.exit_code, 0) << result.err;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Faults, EmptyOrGarbagePcdIsNamedNotACrash) {
  testing::Sandbox sandbox("faults_pcd");
  makeDataset(sandbox);
  sandbox.write("ds/scans/000003.pcd", "");
  auto result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg slam: error: ds/scans/000003.pcd: empty file, not a PCD file\n");
  EXPECT_FALSE(sandbox.exists("out"));

  sandbox.write("ds/scans/000003.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\n\x01\x02garbage");
  result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/scans/000003.pcd: line 4: not a PCD header line: "
            "\"??garbage\"\n");

  // A header whose last line, "DATA binary", has no line end: no data, not a read past the end.
  sandbox.write("ds/scans/000003.pcd",
                "VERSION 0.7\nFIELDS x y z intensity ring time\nSIZE 4 4 4 4 2 4\n"
                "TYPE F F F F U F\nCOUNT 1 1 1 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA binary");
  result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/scans/000003.pcd: data: 2 points need 44 bytes, the file holds "
            "0\n");

  // A binary file cut short.
  const std::string whole = sandbox.read("ds/scans/000004.pcd");
  sandbox.write("ds/scans/000003.pcd", whole.substr(0, whole.size() - 100));
  result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("ds/scans/000003.pcd: data: "), std::string::npos) << result.err;
  EXPECT_FALSE(sandbox.exists("out"));
}

TEST(Faults, MetadataFieldsAreCheckedWithTheirPointer) {
  testing::Sandbox sandbox("faults_metadata");
  makeDataset(sandbox);
  const json original = json::parse(sandbox.read("ds/metadata.json"));
  json metadata = original;
  for (auto& row : metadata["extrinsics"]["R_T_L"]["matrix"]) row = {0, 0, 0, 0};
  sandbox.write("ds/metadata.json", metadata.dump());
  auto result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/metadata.json: /extrinsics/R_T_L/matrix: the upper-left 3 × 3 "
            "block is not a rotation (orthonormal with determinant +1)\n");

  metadata = original;
  metadata["seed"] = "seven";
  sandbox.write("ds/metadata.json", metadata.dump());
  result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/metadata.json: /seed: expected a non-negative integer, got a "
            "string\n");

  metadata = original;
  metadata["robot"] = {{"level", 3}};
  sandbox.write("ds/metadata.json", metadata.dump());
  result = sandbox.run("slam ds -q -o out");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/metadata.json: /robot/level: expected a string, got a number\n");
  EXPECT_FALSE(sandbox.exists("out"));
}

TEST(Faults, ShortRunsAndRunsWithoutGroundTruthSayWhatIsMissing) {
  testing::Sandbox sandbox("faults_short");
  auto result = sandbox.run("run builtin:d1 --duration 1 -q -o r");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("  note: APE in M (SE(3)-aligned) not computed: "), std::string::npos)
      << result.out;
  EXPECT_TRUE(sandbox.exists("r/metrics.json"));

  makeDataset(sandbox, "ds", "1");
  fs::remove(sandbox.dir() / "ds/groundtruth.tum");
  result = sandbox.run("slam ds -q -o s");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  const json metrics = json::parse(sandbox.read("s/metrics.json"));
  EXPECT_EQ(metrics["notes"][0], "no ground truth: no APE (a dataset without groundtruth.tum)");
  EXPECT_FALSE(metrics.contains("ape_B"));
}

TEST(Faults, AReplayInAnotherPlanNeedsToBeAskedFor) {
  testing::Sandbox sandbox("faults_other_plan");
  makeDataset(sandbox);
  auto result = sandbox.run("slam ds --plan builtin:d2 -q -o s");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg slam: error: ds/metadata.json: /plan: the dataset was recorded in plan \"D1 "
            "three offices and a corridor\", not in builtin:d2 (give --other-plan to localize in "
            "a different plan on purpose)\n");
  EXPECT_FALSE(sandbox.exists("s"));
  result = sandbox.run("slam ds --plan builtin:d2 --other-plan -q -o s");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  result = sandbox.run("slam ds --plan builtin:d1 -q -o s1");
  EXPECT_EQ(result.exit_code, 0) << result.err;
}

TEST(Faults, ARouteThatGoesNowhereIsAnError) {
  testing::Sandbox sandbox("faults_one_room");
  json plan = bim::testing::twoRoomPlanJson();
  auto& level = plan["levels"][0];
  level["rooms"].erase(1);
  level["doors"] = json::array();
  sandbox.write("plan.json", plan.dump());
  for (const char* command : {"simulate", "run"}) {
    const auto result = sandbox.run(std::string(command) + " plan.json -q -o out");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.err, std::string("isg ") + command +
                              ": error: plan.json: /robot/route: no scan would be recorded: the "
                              "robot has nowhere to go: the route from its start reaches no "
                              "other room or point (a one-room plan, or every door closed); give "
                              "robot.route.waypoints (docs/formats.md)\n");
    EXPECT_FALSE(sandbox.exists("out"));
  }
}

TEST(Faults, ADurationLongerThanTheRouteIsAWarning) {
  testing::Sandbox sandbox("faults_duration");
  const auto result = sandbox.run("simulate builtin:d1 --duration 100000 -q -o ds");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(
      result.err.rfind("isg simulate: warning: --duration 100000 s is longer than the route (", 0),
      0u)
      << result.err;
}

TEST(Determinism, TheThreadCountDoesNotChangeARun) {
  testing::Sandbox sandbox("determinism_threads");
  for (const char* threads : {"1", "2", "4"}) {
    const auto result =
        sandbox.run(std::string("run builtin:d1.asbuilt --duration 8 -q --threads ") + threads +
                    " -o r" + threads);
    ASSERT_EQ(result.exit_code, 0) << result.err;
  }
  // Byte for byte, except the matcher's own timing in sgraph.json (wall-clock seconds).
  auto sgraph = [&](const std::string& dir) {
    json j = json::parse(sandbox.read(dir + "/sgraph.json"));
    j["matching"]["last_match"].erase("seconds");
    return j;
  };
  for (const char* file : {"estimate.tum", "estimate_map.tum", "keyframes.tum"}) {
    EXPECT_TRUE(sandbox.read(std::string("r1/") + file) == sandbox.read(std::string("r2/") + file))
        << file;
    EXPECT_TRUE(sandbox.read(std::string("r1/") + file) == sandbox.read(std::string("r4/") + file))
        << file;
  }
  EXPECT_TRUE(sgraph("r1") == sgraph("r2"));
  EXPECT_TRUE(sgraph("r1") == sgraph("r4"));
}

TEST(Faults, MissingWallsOpenTheWay) {
  // The wall between the two rooms is missing and its door is closed: the tour still reaches
  // the second room, through the gap the missing wall leaves.
  testing::Sandbox sandbox("faults_missing_wall");
  sandbox.write("plan.json", bim::testing::twoRoomPlanJson().dump());
  sandbox.write("scenario.json", R"({"format": "isg.scenario", "version": 1, "plan": "plan.json",
    "as_built": {"missing_walls": ["W5"]}})");
  const auto result = sandbox.run("simulate scenario.json -q -o ds");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("2 rooms visited"), std::string::npos) << result.out;
}

TEST(Faults, DamagedTumFilesAreNamedWithTheirLine) {
  testing::Sandbox sandbox("faults_tum");
  sandbox.write("a.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n0.5 2 0 0 0 0 0 1\n");
  sandbox.write("b.tum", "# nothing\n");
  auto result = sandbox.run("eval a.tum a.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg eval: error: a.tum: line 3: time 0.500000 does not come after the previous "
            "pose's 1.000000 (poses must be in increasing time)\n");
  result = sandbox.run("eval b.tum b.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg eval: error: b.tum: no poses (a TUM file holds one pose per line)\n");
  result = sandbox.run("eval /dev/zero b.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg eval: error: /dev/zero: not a regular file\n");
}

TEST(Faults, DamagedMetricsAreNamedByIsgTable) {
  testing::Sandbox sandbox("faults_metrics");
  fs::create_directories(sandbox.dir() / "r");
  sandbox.write("r/metrics.json", "{\"world\": \"d1\", \"method\": ");
  const auto result = sandbox.run("table r");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(
      result.err.rfind("isg table: error: r/metrics.json: invalid JSON at line 1, column ", 0), 0u)
      << result.err;
}

TEST(Faults, StaleTemporaryFoldersOfKilledRunsAreRemoved) {
  testing::Sandbox sandbox("faults_stale");
  // What a SIGKILLed run leaves: a hidden temporary folder named after a process that is gone.
  fs::create_directories(sandbox.dir() / ".ds.partial999999999/scans");
  fs::create_directories(sandbox.dir() / ".other.partial999999999");
  makeDataset(sandbox, "ds", "1");
  EXPECT_EQ(entries(sandbox.dir()), (std::vector<std::string>{".other.partial999999999", "ds"}));
}

TEST(Faults, InterruptedSimulationLeavesNothing) {
  testing::Sandbox sandbox("faults_interrupt");
  for (const char* signal : {"INT", "TERM"}) {
    const std::string command = "cd '" + sandbox.dir().string() + "' && ('" +
                                std::string(ISG_EXECUTABLE) +
                                "' simulate builtin:d3 -q -o ds 2> err.txt & pid=$!; sleep 1.5; "
                                "kill -" +
                                signal + " $pid; wait $pid; echo $? > code.txt)";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const int code = std::stoi(sandbox.read("code.txt"));
    EXPECT_EQ(code, std::string(signal) == "INT" ? 130 : 143);
    EXPECT_EQ(sandbox.read("err.txt"),
              std::string(signal) == "INT"
                  ? "isg simulate: interrupted (Ctrl-C); nothing was written\n"
                  : "isg simulate: stopped by signal 15; nothing was written\n");
    EXPECT_EQ(entries(sandbox.dir()), (std::vector<std::string>{"code.txt", "err.txt"}));
    fs::remove(sandbox.dir() / "code.txt");
    fs::remove(sandbox.dir() / "err.txt");
  }
}

// A full disk and a read-only folder need a small tmpfs: root only. Each test process mounts its
// own: CTest runs the tests of this fixture side by side, and a shared mount point let one test's
// read-only tmpfs land on the other's.
class FullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a small tmpfs";
    fs::create_directories(mount_point_);
  }
  void TearDown() override {
    if (mounted_) ::umount(mount_point_.c_str());
    fs::remove_all(mount_point_);
  }
  bool mount(const char* options) {
    mounted_ = ::mount("tmpfs", mount_point_.c_str(), "tmpfs", 0, options) == 0;
    return mounted_;
  }
  fs::path mount_point_ =
      fs::temp_directory_path() / ("isg_cli_test_full_disk_" + std::to_string(::getpid()));
  bool mounted_ = false;
};

TEST_F(FullDisk, SimulateOnAFullDiskIsAnErrorAndLeavesNothing) {
  if (!mount("size=1m")) GTEST_SKIP() << "cannot mount tmpfs here";
  testing::Sandbox sandbox("faults_full_disk");
  const auto result = sandbox.run("simulate builtin:d1 -q -o " + (mount_point_ / "ds").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find(": cannot write: No space left on device\n"), std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.rfind("isg simulate: error: " + (mount_point_ / "ds/scans/").string(), 0),
            0u)
      << result.err;
  EXPECT_TRUE(entries(mount_point_).empty());
}

// The bag cannot be written: the dataset written before it goes too, and the message says why.
TEST_F(FullDisk, SimulateWhoseBagFillsTheDiskLeavesNeitherBagNorDataset) {
  if (!mount("size=1m")) GTEST_SKIP() << "cannot mount tmpfs here";
  testing::Sandbox sandbox("faults_full_disk_bag");
  const auto result = sandbox.run("simulate builtin:d1 --duration 5 -q -o ds --rosbag " +
                                  (mount_point_ / "ds.bag").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find(": cannot write: No space left on device\n"), std::string::npos)
      << result.err;
  EXPECT_FALSE(sandbox.exists("ds"));
  EXPECT_TRUE(entries(mount_point_).empty());
}

TEST_F(FullDisk, ReadOnlyOutputIsAnErrorBeforeTheRun) {
  if (!mount("ro,size=1m")) GTEST_SKIP() << "cannot mount tmpfs here";
  testing::Sandbox sandbox("faults_read_only");
  for (const char* command : {"simulate builtin:d1", "run builtin:d1"}) {
    const auto result =
        sandbox.run(std::string(command) + " -q -o " + (mount_point_ / "out").string());
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find((mount_point_ / "out").string() +
                              ": cannot write: Read-only file system\n"),
              std::string::npos)
        << result.err;
  }
}

}  // namespace
}  // namespace isg::cli
