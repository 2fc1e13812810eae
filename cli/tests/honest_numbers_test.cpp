// Numbers that cannot be right are input errors, never a table entry with exit 0; the generator
// keeps its advertised ranges or says the one that holds; an export checks a dataset against its
// metadata.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* kPose = " 0 0 0 0 0 0 1\n";

TEST(HonestNumbers, TumValuesOutOfRangeAreInputErrors) {
  testing::Sandbox sandbox("numbers_tum");
  sandbox.write("gt.tum", std::string("0") + kPose + "1" + kPose + "2" + kPose);
  sandbox.write("huge.tum", "0 1e308 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  const auto huge = sandbox.run("eval gt.tum huge.tum");
  EXPECT_EQ(huge.exit_code, 1);
  EXPECT_THAT(huge.err, HasSubstr("huge.tum: line 1: tx 1e+308 is out of range (at most 1e9 m "
                                  "from the origin)"));
  sandbox.write("early.tum", std::string("-1e300") + kPose + "1" + kPose);
  const auto early = sandbox.run("eval gt.tum early.tum");
  EXPECT_EQ(early.exit_code, 1);
  EXPECT_THAT(early.err, HasSubstr("line 1: time -1e+300 is out of range (|t| at most 1e10 s)"));
  // An estimate that starts before the ground truth was localized when it began: time 0.
  sandbox.write("before.tum", std::string("-5") + kPose + "1" + kPose + "2" + kPose);
  const auto before = sandbox.run("eval gt.tum before.tum --json");
  ASSERT_EQ(before.exit_code, 0) << before.err;
  EXPECT_EQ(nlohmann::json::parse(before.out)["time_to_localize"], 0.0);
}

TEST(HonestNumbers, RpeWithNoPairsIsNotComputable) {
  testing::Sandbox sandbox("numbers_rpe");
  std::string text;
  for (int i = 0; i < 88; ++i) text += std::to_string(i) + kPose;
  sandbox.write("a.tum", text);
  const auto r = sandbox.run("eval a.tum a.tum --rpe 1000000");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("RPE w.r.t. translation part (m) for delta = 1000000 (frames): not "
                               "computable: no two associated poses are 1000000 frames apart (88 "
                               "poses associated)"));
  const auto json = sandbox.run("eval a.tum a.tum --rpe 1000000 --json");
  const auto doc = nlohmann::json::parse(json.out);
  EXPECT_TRUE(doc["rpe"].is_null());
  EXPECT_THAT(doc["rpe_note"].get<std::string>(), HasSubstr("not computable"));
}

TEST(HonestNumbers, MetricsAndBaselinesHoldFiniteNonNegativeMeasures) {
  testing::Sandbox sandbox("numbers_metrics");
  ASSERT_EQ(sandbox.run("run builtin:d2 --method dead-reckoning --duration 3 -o r -q").exit_code,
            0);
  auto metrics = nlohmann::json::parse(sandbox.read("r/metrics.json"));
  metrics["ape_B"]["rmse"] = -0.5;
  sandbox.write("r/metrics.json", metrics.dump(2));
  const auto negative = sandbox.run("table r");
  EXPECT_EQ(negative.exit_code, 1);
  EXPECT_THAT(negative.err, HasSubstr("r/metrics.json: /ape_B/rmse: must be >= 0, got -0.5"));
  metrics["ape_B"]["rmse"] = 0.02;
  sandbox.write("r/metrics.json", metrics.dump(2));
  sandbox.write("base.csv", "world,odometry\nd2,nan\n");
  const auto nan = sandbox.run("table r --baseline base.csv");
  EXPECT_EQ(nan.exit_code, 1);
  EXPECT_THAT(nan.err,
              HasSubstr("base.csv: line 2, odometry: \"nan\" is not a finite number >= 0"));
  sandbox.write("base.csv", "world,odometry\nd2,inf\n");
  EXPECT_EQ(sandbox.run("table r --baseline base.csv").exit_code, 1);
}

TEST(HonestNumbers, SeedsOnTheCommandLineAreCheckedLikeTheSuites) {
  testing::Sandbox sandbox("numbers_seed");
  for (const char* seed : {"-1", "18446744073709551616", "1.5", "0x10", ""}) {
    const auto r =
        sandbox.run(std::string("run builtin:d1 --duration 1 -o r --seed '") + seed + "'");
    EXPECT_EQ(r.exit_code, 2) << seed;
    EXPECT_THAT(r.err, HasSubstr("expected an integer 0 … 18446744073709551615")) << seed;
  }
  EXPECT_FALSE(sandbox.exists("r"));
  const auto biggest =
      sandbox.run("generate hall -o g --seed 18446744073709551615 --count 2 -q --no-verify");
  EXPECT_EQ(biggest.exit_code, 1);
  EXPECT_THAT(biggest.err, HasSubstr("pass 2^64 - 1"));
}

TEST(HonestGenerator, CountsAndRangesAreWhatItSays) {
  testing::Sandbox sandbox("generator_ranges");
  const auto twice = sandbox.run("generate hall hall -o g -q");
  ASSERT_EQ(twice.exit_code, 0) << twice.err;
  EXPECT_THAT(twice.out, HasSubstr("wrote g: 1 building (1 plan and 1 as-built scenario)"));
  // The documented narrowest corridor tours every room in every family with arms.
  for (const char* family : {"l-shape", "t-shape", "u-shape"}) {
    const auto r = sandbox.run(std::string("generate ") + family +
                               " --corridor-width 1.2 -o narrow-" + family + " -q");
    EXPECT_EQ(r.exit_code, 0) << family << ": " << r.err;
  }
  // Corridors narrower than what a wall leaves free are refused by name.
  const auto walls = sandbox.run("generate office --corridor-width 1.2 --wall-thickness 0.5 -o x");
  EXPECT_EQ(walls.exit_code, 1);
  EXPECT_THAT(walls.err, HasSubstr("--corridor-width: must be at least 1 m more than the wall"));
  // A hotel is one corridor: thousands of rooms are longer than a level may be; the message says
  // how many fit.
  const auto hotel = sandbox.run("generate hotel --rooms 3000 -o h -q");
  EXPECT_EQ(hotel.exit_code, 1);
  EXPECT_THAT(hotel.err, HasSubstr("--rooms: 3000 offices make a plan isg check refuses ("));
  EXPECT_THAT(hotel.err, HasSubstr("at most 1000 m on a side"));
  EXPECT_THAT(hotel.err, HasSubstr("; a hotel of these parameters holds at most "));
  EXPECT_FALSE(sandbox.exists("h"));
}

TEST(HonestGenerator, UnverifiedBuildingsStillReadAsIsgCheckReadsThem) {
  testing::Sandbox sandbox("generator_noverify");
  const auto r =
      sandbox.run("generate office --rooms 2000 --clutter-per-room 4 --no-verify -o g -q");
  if (r.exit_code == 0) {
    EXPECT_EQ(sandbox.run("check g/office-1.asbuilt.json").exit_code, 0);
  } else {
    // Refused with the count that works, never written half-checked.
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("of these parameters holds at most"));
    EXPECT_FALSE(sandbox.exists("g"));
  }
}

// A dataset whose metadata lies is never exported as if it told the truth.
TEST(HonestExport, TheDatasetIsCheckedAgainstItsMetadata) {
  testing::Sandbox sandbox("export_metadata");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 2 -o ds -q").exit_code, 0);
  const std::string original = sandbox.read("ds/metadata.json");
  const auto lie = [&](const std::string& pointer, const nlohmann::json& value) {
    auto m = nlohmann::json::parse(original);
    m[nlohmann::json::json_pointer(pointer)] = value;
    sandbox.write("ds/metadata.json", m.dump(2));
    const auto r = sandbox.run("export ds --rosbag b.bag -q");
    sandbox.write("ds/metadata.json", original);
    EXPECT_FALSE(sandbox.exists("b.bag")) << pointer;
    return r;
  };
  const auto imu_rate = lie("/imu/rate_hz", 400);
  EXPECT_EQ(imu_rate.exit_code, 1);
  EXPECT_THAT(imu_rate.err, HasSubstr("ds/metadata.json: /imu/rate_hz: says 400 Hz, "));
  EXPECT_THAT(lie("/imu/samples", 7).err, HasSubstr("/imu/samples: says 7 samples"));
  EXPECT_THAT(lie("/lidar/rate_hz", 20).err, HasSubstr("/lidar/rate_hz: says 20 Hz"));
  EXPECT_THAT(lie("/lidar/scans", 3).err, HasSubstr("/lidar/scans: says 3 scans, the dataset has"));
  EXPECT_THAT(lie("/duration_s", 10).err, HasSubstr("/duration_s: says 10 s, the last scan's"));
  // An IMU declared but with an empty file.
  const std::string imu = sandbox.read("ds/imu.csv");
  sandbox.write("ds/imu.csv", imu.substr(0, imu.find('\n') + 1));
  const auto empty = sandbox.run("export ds --rosbag b.bag -q");
  EXPECT_EQ(empty.exit_code, 1);
  EXPECT_THAT(empty.err, HasSubstr("/imu/samples: says"));
  EXPECT_THAT(empty.err, HasSubstr("has none"));
  sandbox.write("ds/imu.csv", imu);
  // scans.tum shifted in time by 0.5 s: its poses are no longer the LiDAR's at those stamps.
  std::istringstream rows(sandbox.read("ds/scans.tum"));
  std::string shifted, line;
  while (std::getline(rows, line)) {
    if (line.empty() || line[0] == '#') {
      shifted += line + "\n";
      continue;
    }
    std::istringstream fields(line);
    double t = 0;
    fields >> t;
    std::string rest;
    std::getline(fields, rest);
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.9f", t + 0.5);
    shifted += stamp + rest + "\n";
  }
  const std::string scans = sandbox.read("ds/scans.tum");
  sandbox.write("ds/scans.tum", shifted);
  const auto moved = sandbox.run("export ds --rosbag b.bag -q");
  EXPECT_EQ(moved.exit_code, 1);
  EXPECT_THAT(moved.err, HasSubstr("ds/scans.tum: scan "));
  sandbox.write("ds/scans.tum", scans);
  EXPECT_EQ(sandbox.run("export ds --rosbag b.bag -q").exit_code, 0);
}

// Scans are matched to their stamps by name: a dataset whose scans/ skips a number (a renamed or
// missing file, a name of another form) is refused naming the first missing or extra scan, never
// exported with every later cloud on the previous cloud's stamp.
TEST(HonestExport, ScansMatchTheirStampsOneToOne) {
  testing::Sandbox sandbox("export_gap");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 2 -o ds -q").exit_code, 0);
  const fs::path scans = sandbox.dir() / "ds/scans";
  const auto refused = [&](const std::string& from, const std::string& to) {
    fs::rename(scans / from, scans / to);
    const auto r = sandbox.run("export ds --rosbag b.bag -q");
    fs::rename(scans / to, scans / from);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_FALSE(sandbox.exists("b.bag")) << to;
    return r.err;
  };
  const std::string rule =
      " s in ds/scans.tum; scan k is scans/NNNNNN.pcd, k from 000000 in scans.tum's order; 20 "
      "stamps, 20 .pcd files in scans/; scans/";
  const std::string renamed = refused("000010.pcd", "000030.pcd");
  EXPECT_THAT(
      renamed,
      HasSubstr("isg export: error: ds/scans/000010.pcd: missing: no scan for stamp 10 (t = "));
  EXPECT_THAT(renamed, HasSubstr(rule + "000030.pcd is no stamp's scan)"));
  const std::string short_name = refused("000010.pcd", "10.pcd");
  EXPECT_THAT(short_name, HasSubstr("ds/scans/000010.pcd: missing: no scan for stamp 10"));
  EXPECT_THAT(short_name, HasSubstr(rule + "10.pcd is no stamp's scan)"));
  // The last scan missing: one fewer file than stamps.
  fs::rename(scans / "000019.pcd", sandbox.dir() / "aside.pcd");
  const auto last = sandbox.run("export ds --rosbag b.bag -q");
  EXPECT_THAT(last.err, HasSubstr("ds/scans/000019.pcd: missing: no scan for stamp 19"));
  EXPECT_THAT(last.err, HasSubstr("; 20 stamps, 19 .pcd files in scans/)"));
  fs::rename(sandbox.dir() / "aside.pcd", scans / "000019.pcd");
  // A scan no stamp names.
  fs::copy_file(scans / "000019.pcd", scans / "000020.pcd");
  const auto extra = sandbox.run("export ds --rosbag b.bag -q");
  EXPECT_EQ(extra.exit_code, 1);
  EXPECT_EQ(extra.err,
            "isg export: error: ds/scans/000020.pcd: no stamp's scan: scan k is "
            "scans/NNNNNN.pcd, k from 000000 in scans.tum's order, and ds/scans.tum has 20 "
            "stamps (000000.pcd to 000019.pcd)\n");
  // Replays read scans the same way.
  EXPECT_THAT(sandbox.run("slam ds --method odometry -o r -q").err,
              HasSubstr("ds/scans/000020.pcd: no stamp's scan"));
  fs::remove(scans / "000020.pcd");
  EXPECT_EQ(sandbox.run("export ds --rosbag b.bag -q").exit_code, 0);
}

}  // namespace
}  // namespace isg::cli
