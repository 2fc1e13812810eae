// deviations.bcf end to end (docs/deviations.md, "BCF"): a run on D1 built with a wall shifted,
// a wall turned and a partition the plan lacks writes a BCF 3.0 archive whose every document
// validates against buildingSMART's schemas (xmllint, the schemas kept in run/bcf/tests/bcf-xml);
// `isg bcf` writes it again, the same bytes for the same date; a plan imported from IFC reports
// its shifted wall under the wall's GlobalId; bad input is refused naming the file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const fs::path kSchemas = fs::path(ISG_SOURCE_DIR) / "run/bcf/tests/bcf-xml";

// The archive unpacked by Python's zipfile into `into`; its names, one a line.
std::string unpack(const testing::Sandbox& sandbox, const std::string& archive,
                   const std::string& into) {
  const std::string script =
      "import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); assert z.testzip() is None; "
      "z.extractall(sys.argv[2]); print('\\n'.join(z.namelist()))";
  const std::string command = "cd '" + sandbox.dir().string() + "' && /usr/bin/python3 -c \"" +
                              script + "\" " + archive + " " + into + " > names.txt";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return sandbox.read("names.txt");
}

// xmllint's verdict on every document of an unpacked archive: "" when all are valid.
std::string invalidDocuments(const testing::Sandbox& sandbox, const std::string& folder) {
  std::string failures;
  const auto check = [&](const fs::path& document, const char* schema) {
    const std::string command = "xmllint --noout --schema '" + (kSchemas / schema).string() +
                                "' '" + document.string() + "' > /dev/null 2>&1";
    if (std::system(command.c_str()) != 0) failures += document.string() + "\n";
  };
  const fs::path root = sandbox.dir() / folder;
  check(root / "bcf.version", "version.xsd");
  check(root / "extensions.xml", "extensions.xsd");
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!entry.is_directory()) continue;
    check(entry.path() / "markup.bcf", "markup.xsd");
    check(entry.path() / "viewpoint.bcfv", "visinfo.xsd");
  }
  return failures;
}

std::vector<std::string> titles(const testing::Sandbox& sandbox, const std::string& folder) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(sandbox.dir() / folder)) {
    if (!entry.is_directory()) continue;
    const std::string markup =
        sandbox.read((fs::path(folder) / entry.path().filename() / "markup.bcf").string());
    std::smatch title;
    if (std::regex_search(markup, title, std::regex("<Title>([^<]*)</Title>"))) {
      found.push_back(title[1]);
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

TEST(BcfReport, ARunWritesAValidArchiveOfItsDeviationsAndIsgBcfWritesItAgain) {
  const testing::Sandbox sandbox("bcf_report");
  sandbox.write(
      "d1.json",
      json{
          {"format", "isg.scenario"},
          {"version", 1},
          {"plan", std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json"},
          {"seed", 1},
          {"as_built",
           {{"wall_shifts", {{{"wall", "W7"}, {"offset", 0.25}}}},
            {"wall_rotations", {{{"wall", "W6"}, {"angle_deg", 4.0}, {"about", "start"}}}},
            {"extra_walls", {{{"start", {10.0, 5.0}}, {"end", {10.0, 7.0}}, {"thickness", 0.1}}}}}}}
          .dump());
  const auto run = sandbox.run("run d1.json -o r -q");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("deviations.bcf: 3 topics for BIM tools"), std::string::npos) << run.out;
  const std::string names = unpack(sandbox, "r/deviations.bcf", "x");
  EXPECT_EQ(names.rfind("bcf.version\nextensions.xml\n", 0), 0u) << names;
  EXPECT_EQ(invalidDocuments(sandbox, "x"), "");
  EXPECT_EQ(titles(sandbox, "x"),
            (std::vector<std::string>{"Extra wall 1, 2.16 m long", "Wall W6 turned +4.0°",
                                      "Wall W7 shifted +0.25 m"}));
  // Each topic's snapshot is an 800 × 600 PNG (its IHDR), rendered from its viewpoint.
  std::size_t snapshots = 0;
  for (const auto& entry : fs::directory_iterator(sandbox.dir() / "x")) {
    if (!entry.is_directory()) continue;
    const std::string png =
        sandbox.read((fs::path("x") / entry.path().filename() / "snapshot.png").string());
    ASSERT_GT(png.size(), 24u);
    EXPECT_EQ(png.substr(0, 8), "\x89PNG\r\n\x1a\n");
    EXPECT_EQ(png.substr(16, 8), std::string("\0\0\x03\x20\0\0\x02\x58", 8));
    ++snapshots;
  }
  EXPECT_EQ(snapshots, 3u);

  // isg bcf: the same topics again; with SOURCE_DATE_EPOCH, the same bytes twice.
  ::setenv("SOURCE_DATE_EPOCH", "1796630400", 1);
  const auto first = sandbox.run("bcf r");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.out, "isg bcf: wrote r/deviations.bcf, 3 topics\n");
  const std::string bytes = sandbox.read("r/deviations.bcf");
  ASSERT_EQ(sandbox.run("bcf r").exit_code, 0);
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(sandbox.read("r/deviations.bcf"), bytes);
  unpack(sandbox, "r/deviations.bcf", "y");
  EXPECT_EQ(invalidDocuments(sandbox, "y"), "");
  EXPECT_EQ(titles(sandbox, "y"), titles(sandbox, "x"));
  EXPECT_NE(sandbox.read("y/" + names.substr(names.find('/') - 36, 36) + "/markup.bcf")
                .find("<CreationDate>2026-12-07T08:00:00Z</CreationDate>"),
            std::string::npos);
}

TEST(BcfReport, BadInputIsRefusedNamingTheFile) {
  const testing::Sandbox sandbox("bcf_bad_input");
  auto r = sandbox.run("bcf nowhere");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("nowhere/deviations.json: no deviation report"), std::string::npos) << r.err;
  ASSERT_EQ(sandbox.run("run builtin:d1 --duration 30 -o r -q").exit_code, 0);
  // Another world than the run's: refused by its content hash.
  r = sandbox.run("bcf r --world builtin:d2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not the world run r was made in"), std::string::npos) << r.err;
  // A file at deviations.bcf that is not ours is never replaced.
  sandbox.write("r/deviations.bcf", "my notes");
  r = sandbox.run("bcf r");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(sandbox.read("r/deviations.bcf"), "my notes");
  EXPECT_EQ(sandbox.run("bcf --help").exit_code, 0);
}

TEST(BcfReport, APlanImportedFromIfcReportsAShiftedWallUnderItsGlobalId) {
  const testing::Sandbox sandbox("bcf_ifc");
  const std::string model = std::string(ISG_SOURCE_DIR) + "/ifc/tests/models/duplex.ifc";
  ASSERT_EQ(sandbox.run("import " + model + " -o duplex.json").exit_code, 0);
  // An inner wall of the ground floor's western unit, 4.2 m long, built 20 cm off.
  constexpr const char* kWall = "2O2Fr$t4X7Zf8NOew3FNbT";
  sandbox.write("duplex.scenario.json",
                json{{"format", "isg.scenario"},
                     {"version", 1},
                     {"plan", "duplex.json"},
                     {"seed", 1},
                     {"as_built", {{"wall_shifts", {{{"wall", kWall}, {"offset", 0.2}}}}}}}
                    .dump());
  // The duplex's two units mirror each other: the run starts from its true pose.
  const auto run = sandbox.run("run duplex.scenario.json --start-pose truth -o r -q");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  unpack(sandbox, "r/deviations.bcf", "x");
  EXPECT_EQ(invalidDocuments(sandbox, "x"), "");
  bool found = false;
  for (const auto& entry : fs::directory_iterator(sandbox.dir() / "x")) {
    if (!entry.is_directory()) continue;
    const std::string folder = "x/" + entry.path().filename().string();
    const std::string viewpoint = sandbox.read(folder + "/viewpoint.bcfv");
    if (viewpoint.find(std::string("<Component IfcGuid=\"") + kWall + "\">") == std::string::npos) {
      continue;
    }
    found = true;
    std::smatch shift;
    const std::string markup = sandbox.read(folder + "/markup.bcf");
    ASSERT_TRUE(std::regex_search(markup, shift, std::regex("shifted ([-+0-9.]+) m</Title>")))
        << markup;
    EXPECT_NEAR(std::stod(shift[1]), 0.2, 0.03) << markup;
  }
  EXPECT_TRUE(found) << "no topic selects " << kWall;
  // deviations.json names each wall's GlobalId too.
  bool in_report = false;
  const json report = json::parse(sandbox.read("r/deviations.json"));
  for (const auto& wall : report["walls"]) {
    if (wall["wall"] == kWall) in_report = wall.value("ifc_guid", "") == kWall;
  }
  EXPECT_TRUE(in_report);
}

}  // namespace
}  // namespace isg::cli
