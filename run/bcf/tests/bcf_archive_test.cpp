// The BCF archive of a deviation report checked by tools that are not ours: Python's zipfile
// lists and unpacks it, xmllint validates every document against buildingSMART's BCF 3.0 schemas
// (kept unmodified in run/bcf/tests/bcf-xml). And the topics: which elements get one, under which
// GlobalId, with which numbers.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/output_path.hpp"
#include "run/bcf/bcf_archive.hpp"
#include "run/bcf/bcf_xml.hpp"

namespace isg::run::bcf {
namespace {

namespace fs = std::filesystem;

const fs::path kSchemas = fs::path(ISG_SOURCE_DIR) / "run/bcf/tests/bcf-xml";
constexpr const char* kW1Guid = "2O2Fr$t4X7Zf8NOew3FNr2";
constexpr const char* kC1Guid = "0hXw6Hw$zD8AXkvTbpnXB3";

// A level of four walls (W1 with its GlobalId), a column with one.
bim::Plan twoRoomPlan() {
  bim::Plan plan;
  plan.name = "office";
  bim::Level level;
  level.id = "L1";
  level.elevation = 3.0;
  level.height = 2.8;
  const auto wall = [&](const char* id, Eigen::Vector2d a, Eigen::Vector2d b) {
    bim::Wall w;
    w.id = id;
    w.start = a;
    w.end = b;
    w.thickness = 0.2;
    w.height = 2.8;
    level.walls.push_back(w);
  };
  wall("W1", {0, 0}, {8, 0});
  wall("W2", {8, 0}, {8, 6});
  wall("W3", {8, 6}, {0, 6});
  wall("W4", {0, 6}, {0, 0});
  level.walls[0].ifc_guid = kW1Guid;
  bim::Column column;
  column.id = "C1";
  column.center = {4, 3};
  column.size = {0.4, 0.4};
  column.height = 2.8;
  column.ifc_guid = kC1Guid;
  level.columns.push_back(column);
  plan.levels.push_back(level);
  return plan;
}

slam::WallDeviation wallDeviation(const bim::Plan& plan, const char* id, slam::WallStatus status) {
  const bim::Wall& w = *plan.levels[0].findWall(id);
  slam::WallDeviation d;
  d.wall = id;
  d.level = "L1";
  d.status = status;
  d.planned_start = w.start;
  d.planned_end = w.end;
  d.thickness = w.thickness;
  d.shift_threshold_m = 0.06;
  d.angle_threshold_deg = 1.5;
  d.placement_sigma_m = 0.008;
  d.progress.status = slam::ProgressStatus::kBuilt;
  return d;
}

// W1 shifted 0.2 m, W2 missing, W3 as planned, W4 built in part, C1 moved, one extra wall.
slam::DeviationReport report(const bim::Plan& plan) {
  slam::DeviationReport r;
  r.levels = {"L1"};
  r.walls.push_back(wallDeviation(plan, "W1", slam::WallStatus::kShifted));
  r.walls.back().offset_m = 0.2;
  r.walls.back().offset_sigma_m = 0.009;
  r.walls.back().angle_deg = 0.1;
  r.walls.back().observed_share = 0.9;
  r.walls.back().evidence.push_back({.plane = 3, .side = -1, .length_m = 7.2, .observations = 12});
  r.walls.push_back(wallDeviation(plan, "W2", slam::WallStatus::kMissing));
  r.walls.back().progress.status = slam::ProgressStatus::kNotBuilt;
  r.walls.push_back(wallDeviation(plan, "W3", slam::WallStatus::kAsPlanned));
  r.walls.push_back(wallDeviation(plan, "W4", slam::WallStatus::kAsPlanned));
  r.walls.back().progress.status = slam::ProgressStatus::kPartlyBuilt;
  r.walls.back().progress.planned_m = 6.0;
  r.walls.back().progress.built_m = 2.5;
  r.walls.back().progress.not_built_m = 3.5;
  slam::ColumnDeviation c;
  c.column = "C1";
  c.level = "L1";
  c.status = slam::ColumnStatus::kMoved;
  c.planned_centre = {4, 3};
  c.offset_m = Eigen::Vector2d(0.12, -0.03);
  c.directions_measured = 2;
  r.columns.push_back(c);
  r.extra_walls.push_back({"L1", {2, 2}, {5, 2}, {7}});
  return r;
}

// A 1 × 1 grey PNG (its chunks and CRCs made with Python's zlib); the archive stores whatever
// bytes the snapshot maker gives.
const std::string kTinyPng(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52"
    "\x00\x00\x00\x01\x00\x00\x00\x01\x08\x02\x00\x00\x00\x90\x77\x53"
    "\xde\x00\x00\x00\x0c\x49\x44\x41\x54\x78\x9c\x63\x68\x68\x68\x00"
    "\x00\x03\x04\x01\x81\x4b\xd3\xd2\x10\x00\x00\x00\x00\x49\x45\x4e"
    "\x44\xae\x42\x60\x82",
    69);

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (pipe != nullptr && std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return status == 0 ? out : "FAILED(" + std::to_string(status) + "): " + out;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class BcfArchive : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isg-bcf-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST(BcfTopics, OneTopicPerElementOffThePlanUnderItsGlobalId) {
  const bim::Plan plan = twoRoomPlan();
  const auto topics = deviationTopics(report(plan), plan, {"sha256:abc", "is_graphs seed 1"});
  ASSERT_EQ(topics.size(), 5u);  // W1, W2, W4, C1, the extra wall; not W3
  EXPECT_EQ(topics[0].title, "Wall W1 shifted +0.20 m");
  EXPECT_EQ(topics[0].ifc_guid, kW1Guid);
  EXPECT_EQ(topics[0].labels,
            (std::vector<std::string>{"Shifted", "Installed, out of tolerance", "Wall"}));
  EXPECT_NE(topics[0].description.find("Offset +0.200 m ± 0.009 m"), std::string::npos)
      << topics[0].description;
  EXPECT_NE(topics[0].description.find("placement there included: 0.008 m"), std::string::npos);
  EXPECT_EQ(topics[1].title, "Wall W2 missing");
  EXPECT_EQ(topics[1].ifc_guid, "");  // the plan has none: selected by its plan id
  EXPECT_EQ(topics[2].title, "Wall W4 built in part");
  EXPECT_NE(topics[2].description.find("2.50 m standing, 3.50 m not built"), std::string::npos);
  EXPECT_EQ(topics[3].title, "Column C1 moved");
  EXPECT_EQ(topics[3].ifc_guid, kC1Guid);
  EXPECT_EQ(topics[4].title, "Extra wall 1, 3.00 m long");
  // W1 was seen from its right face (side −1): the camera stands south of it (y < 0), above the
  // level's floor (3 m), looking down at its middle.
  const TopicCamera& camera = topics[0].camera;
  EXPECT_LT(camera.eye.y(), 0.0);
  EXPECT_GT(camera.eye.z(), 3.0 + 1.0);
  EXPECT_NEAR(camera.target.x(), 4.0, 1e-9);
  EXPECT_NEAR(camera.target.z(), 4.0, 1e-9);
  EXPECT_NEAR(camera.direction().dot(camera.up()), 0.0, 1e-12);
  EXPECT_GT(camera.up().z(), 0.0);
  EXPECT_NEAR(topics[0].outline.floor_z, 3.0, 1e-12);
  EXPECT_NEAR(topics[0].outline.top_z, 5.8, 1e-12);
  // A topic is the element's in its world; its viewpoint the run's.
  const auto again = deviationTopics(report(plan), plan, {"sha256:abc", "is_graphs seed 2"});
  EXPECT_EQ(again[0].guid, topics[0].guid);
  EXPECT_NE(again[0].viewpoint_guid, topics[0].viewpoint_guid);
  const auto other = deviationTopics(report(plan), plan, {"sha256:abd", "is_graphs seed 1"});
  EXPECT_NE(other[0].guid, topics[0].guid);
  // A replay has no world hash: its plan's content names its topics.
  const TopicNames replay = topicNames("", plan, "is_graphs", 1);
  EXPECT_EQ(replay.world_hash.rfind("sha256:", 0), 0u);
  EXPECT_EQ(replay.run, "is_graphs seed 1");
  bim::Plan moved = plan;
  moved.levels[0].walls[1].end.x() += 0.1;
  EXPECT_NE(topicNames("", moved, "is_graphs", 1).world_hash, replay.world_hash);
  EXPECT_EQ(topicNames("sha256:abc", plan, "is_graphs", 1).world_hash, "sha256:abc");
}

TEST_F(BcfArchive, EveryDocumentValidatesAgainstBuildingSmartsSchemas) {
  const bim::Plan plan = twoRoomPlan();
  const auto topics = deviationTopics(report(plan), plan, {"sha256:abc", "is_graphs seed 1"});
  const fs::path file = dir_ / "deviations.bcf";
  writeArchive(file, topics,
               {.created = 1796630400, .snapshot = [](const Topic&) { return kTinyPng; }});
  EXPECT_TRUE(common::isOurFile(file, common::OutputKind::kBcf));
  const std::string listing = run(
      "/usr/bin/python3 -c \"import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); "
      "assert z.testzip() is None; print('\\n'.join(z.namelist())); z.extractall(sys.argv[2])\" " +
      file.string() + " " + (dir_ / "x").string());
  ASSERT_EQ(listing.find("FAILED"), std::string::npos) << listing;
  const std::string folder = topics[0].guid + "/";
  for (const std::string& name :
       {std::string("bcf.version"), std::string("extensions.xml"), folder, folder + "markup.bcf",
        folder + "viewpoint.bcfv", folder + "snapshot.png"}) {
    EXPECT_NE(listing.find(name + "\n"), std::string::npos) << name << " in\n" << listing;
  }
  // buildingSMART's bcf.version but for the whitespace inside the element, which its own schema
  // does not allow (xmllint refuses the published file).
  std::string published = slurp(kSchemas / "bcf.version");
  published.replace(published.find(">\n</Version>"), 12, "></Version>");
  EXPECT_EQ(slurp(dir_ / "x/bcf.version"), published);
  EXPECT_EQ(slurp(dir_ / "x" / folder / "snapshot.png"), kTinyPng);
  const auto validate = [&](const fs::path& document, const char* schema) {
    return run("xmllint --noout --schema '" + (kSchemas / schema).string() + "' '" +
               document.string() + "'");
  };
  EXPECT_EQ(validate(dir_ / "x/bcf.version", "version.xsd").find("FAILED"), std::string::npos);
  EXPECT_EQ(validate(dir_ / "x/extensions.xml", "extensions.xsd").find("FAILED"),
            std::string::npos);
  for (const Topic& topic : topics) {
    const fs::path topic_dir = dir_ / "x" / topic.guid;
    const std::string markup = validate(topic_dir / "markup.bcf", "markup.xsd");
    EXPECT_EQ(markup.find("FAILED"), std::string::npos) << markup;
    const std::string viewpoint = validate(topic_dir / "viewpoint.bcfv", "visinfo.xsd");
    EXPECT_EQ(viewpoint.find("FAILED"), std::string::npos) << viewpoint;
  }
  const std::string w1 = slurp(dir_ / "x" / folder / "viewpoint.bcfv");
  EXPECT_NE(w1.find(std::string("<Component IfcGuid=\"") + kW1Guid + "\">"), std::string::npos)
      << w1;
  const std::string markup = slurp(dir_ / "x" / folder / "markup.bcf");
  EXPECT_NE(markup.find("<CreationDate>2026-12-07T08:00:00Z</CreationDate>"), std::string::npos)
      << markup;
}

TEST_F(BcfArchive, AValidatorRefusesADocumentTheSchemasDoNotAllow) {
  // The oracle can fail: a topic without its required title is refused.
  std::ofstream(dir_ / "markup.bcf")
      << "<?xml version=\"1.0\"?><Markup><Topic Guid=\"0a0b0c0d-0000-4000-8000-000000000000\" "
         "TopicType=\"Issue\" TopicStatus=\"Open\"><CreationDate>2026-12-07T00:00:00Z"
         "</CreationDate><CreationAuthor>isg</CreationAuthor></Topic></Markup>";
  EXPECT_NE(run("xmllint --noout --schema '" + (kSchemas / "markup.xsd").string() + "' '" +
                (dir_ / "markup.bcf").string() + "'")
                .find("FAILED"),
            std::string::npos);
}

TEST_F(BcfArchive, TheSameTopicsAndDateGiveTheSameBytes) {
  const bim::Plan plan = twoRoomPlan();
  const auto topics = deviationTopics(report(plan), plan, {"sha256:abc", "is_graphs seed 1"});
  writeArchive(dir_ / "a.bcf", topics, {.created = 1796630400});
  writeArchive(dir_ / "b.bcf", topics, {.created = 1796630400});
  EXPECT_EQ(slurp(dir_ / "a.bcf"), slurp(dir_ / "b.bcf"));
  // No snapshot maker: no snapshots, and the markup names none.
  EXPECT_EQ(slurp(dir_ / "a.bcf").find("snapshot.png"), std::string::npos);
}

TEST_F(BcfArchive, AnArchiveThatCannotBeWrittenIsAnErrorNamingIt) {
  const fs::path file = dir_ / "no-such-folder" / "deviations.bcf";
  try {
    writeArchive(file, {}, {});
    FAIL() << "written";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace isg::run::bcf
