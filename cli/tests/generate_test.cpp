#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

using ::testing::HasSubstr;

// Every family's building passes isg check, the same seed gives the same bytes, and a run on a
// generated building localizes.
TEST(Generate, EveryFamilyPassesCheckAndIsReproducible) {
  testing::Sandbox sandbox("generate_all");
  const auto made = sandbox.run("generate all -o a --count 2 --seed 5 -q");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_THAT(made.out, HasSubstr("wrote a: 18 buildings (18 plans and 18 as-built scenarios)"));
  for (const char* family : {"office", "l-shape", "t-shape", "u-shape", "hotel", "twin-wings",
                             "hall", "site", "parking"}) {
    for (const char* seed : {"5", "6"}) {
      const std::string name = std::string(family) + "-" + seed;
      for (const std::string& file : {name + ".json", name + ".asbuilt.json"}) {
        const auto check = sandbox.run("check a/" + file);
        EXPECT_EQ(check.exit_code, 0) << file << ": " << check.err;
        EXPECT_THAT(check.out, HasSubstr("a/" + file + ": ok"));
        EXPECT_EQ(check.err, "") << file;  // not even a warning
      }
    }
  }
  ASSERT_EQ(sandbox.run("generate office -o b --seed 6 -q").exit_code, 0);
  EXPECT_EQ(sandbox.read("b/office-6.json"), sandbox.read("a/office-6.json"));
  EXPECT_EQ(sandbox.read("b/office-6.asbuilt.json"), sandbox.read("a/office-6.asbuilt.json"));
  EXPECT_NE(sandbox.read("a/office-5.json"), sandbox.read("a/office-6.json"));
}

// Past 200 offices an L, T or U is several bands wide (worlds/plan_generator.cpp, armBands): 300
// offices tour (a single corridor of them did not: "the tour cannot reach rooms C1, C2, …"), with
// about the offices asked for, in a floor that fills much of its bounding box.
TEST(Generate, ArmedFloorsOfThreeHundredOfficesTour) {
  testing::Sandbox sandbox("generate_armed");
  for (const char* family : {"l-shape", "u-shape"}) {
    const auto made =
        sandbox.run(std::string("generate ") + family + " -o " + family + " --rooms 300 -q");
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const auto plan =
        nlohmann::json::parse(sandbox.read(std::string(family) + "/" + family + "-1.json"));
    int offices = 0;
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9, area = 0.0;
    for (const auto& room : plan["levels"][0]["rooms"]) {
      if (room["id"].get<std::string>()[0] != 'R') continue;  // corridors are C…
      ++offices;
      const auto& o = room["outline"];
      for (std::size_t i = 0; i < o.size(); ++i) {
        const auto& p = o[i];
        const auto& q = o[(i + 1) % o.size()];
        area += 0.5 *
                (p[0].get<double>() * q[1].get<double>() - q[0].get<double>() * p[1].get<double>());
        x0 = std::min(x0, p[0].get<double>()), x1 = std::max(x1, p[0].get<double>());
        y0 = std::min(y0, p[1].get<double>()), y1 = std::max(y1, p[1].get<double>());
      }
    }
    EXPECT_NEAR(offices, 300, 15) << family;
    // Offices cover over 40 % of the box (a single-corridor L of 300: under 10 %).
    EXPECT_GT(std::abs(area) / ((x1 - x0) * (y1 - y0)), 0.4) << family;
  }
}

// An L of 1000 offices (a box of 174 × 169 m) tours every office: its route grid keeps 5 cm cells
// (sim/occupancy_grid.hpp, kMaxCells). With 6.1 cm cells 167 of its 0.9 m doorways were shut:
// "the tour cannot reach rooms R4, R13, R16, … and 157 more (167 in all)".
TEST(Generate, AnLOfAThousandOfficesTours) {
  testing::Sandbox sandbox("generate_thousand");
  const auto made = sandbox.run("generate l-shape -o l --rooms 1000 -q");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_THAT(made.out, HasSubstr("979 offices in all"));
}

TEST(Generate, AnOfficeParameterGivenForASiteIsSaid) {
  testing::Sandbox sandbox("generate_site");
  const auto made = sandbox.run("generate site -o s --rooms 30 --height 4 -q");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_EQ(made.err,
            "isg generate: warning: --rooms does not apply to the site family (it takes its seed, "
            "--count, --height, --carrier, --missing-columns and --moved-columns only); its "
            "buildings are made without it\n");
  EXPECT_THAT(made.out, HasSubstr("wrote s: 1 building"));
  EXPECT_THAT(sandbox.read("s/site-1.json"), HasSubstr("\"height\": 4.0"));
  // A site has its own slanted corner: it is not sheared.
  const auto sheared = sandbox.run("generate site -o t --shear 20 -q");
  ASSERT_EQ(sheared.exit_code, 0) << sheared.err;
  EXPECT_THAT(sheared.err, HasSubstr("warning: --shear does not apply to the site family"));
  ASSERT_EQ(sandbox.run("generate site -o u -q").exit_code, 0);
  EXPECT_EQ(sandbox.read("t/site-1.json"), sandbox.read("u/site-1.json"));
  // And the other way round: columns as built are the site family's.
  const auto office = sandbox.run("generate office -o o --missing-columns 0.2 -q");
  ASSERT_EQ(office.exit_code, 0) << office.err;
  EXPECT_EQ(office.err,
            "isg generate: warning: --missing-columns applies to the site and parking families "
            "only (the other families' plans have no columns); office buildings are made without "
            "it\n");
}

TEST(Generate, BadParametersNameTheOptionAndWriteNothing) {
  testing::Sandbox sandbox("generate_bad");
  const auto narrow = sandbox.run("generate hotel -o g --corridor-width 0.5");
  EXPECT_EQ(narrow.exit_code, 1);
  EXPECT_EQ(narrow.err,
            "isg generate: error: --corridor-width: must be in [1.2, 6] m (a robot and a door must "
            "fit) (hotel, seed 1)\n");
  EXPECT_FALSE(sandbox.exists("g"));
  const auto shear = sandbox.run("generate office -o g --shear 41");
  EXPECT_EQ(shear.exit_code, 1);
  EXPECT_EQ(shear.err,
            "isg generate: error: --shear: must be in [-40, 40] degrees (office, seed 1)\n");
  EXPECT_FALSE(sandbox.exists("g"));
  const auto family = sandbox.run("generate castle -o g");
  EXPECT_EQ(family.exit_code, 2);
  EXPECT_THAT(family.err, HasSubstr("castle not in {office,l-shape,t-shape,u-shape,hotel,"));
  ASSERT_EQ(sandbox.run("generate hall -o g -q").exit_code, 0);
  const auto again = sandbox.run("generate hall -o g -q");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.err, HasSubstr("exists"));
}

}  // namespace
}  // namespace isg::cli
