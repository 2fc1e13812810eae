#include "eval/table.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace isg::eval {
namespace {

ResultTable sample() {
  ResultTable t;
  t.set("d1", "is-graphs", 0.028);
  t.set("d1", "odometry", 0.099);
  t.set("d2", "is-graphs", std::nullopt);  // failed
  return t;
}

TEST(Table, FormatsAsCsvMarkdownAndLatex) {
  const ResultTable t = sample();
  EXPECT_EQ(formatTable(t, TableFormat::kCsv),
            "world,is-graphs,odometry\nd1,0.028,0.099\nd2,-,\nlocalized correctly,1/2,1/2\n");
  EXPECT_EQ(formatTable(t, TableFormat::kMarkdown),
            "| world | is-graphs | odometry |\n|---|---:|---:|\n"
            "| d1 | 0.028 | 0.099 |\n| d2 | - |  |\n| *localized correctly* | 1/2 | 1/2 |\n");
  const std::string latex = formatTable(t, TableFormat::kLatex, "APE_B");
  EXPECT_NE(formatTable(t, TableFormat::kLatex, "in B; - never, ✗ wrong")
                .find("\\caption{in B; $-$ never, $\\times$ wrong}"),
            std::string::npos);
  EXPECT_NE(latex.find("\\caption{APE\\_B}"), std::string::npos);
  EXPECT_NE(latex.find("\\toprule\nWorld & is-graphs & odometry \\\\\n\\midrule\n"),
            std::string::npos);
  EXPECT_NE(latex.find("d2 & $-$ &  \\\\"), std::string::npos);
  EXPECT_NE(latex.find("\\midrule\nLocalized correctly & 1/2 & 1/2 \\\\\n\\bottomrule"),
            std::string::npos);
}

// A wrong cell is not a correct localization, and a SLAM-only column has no count.
TEST(Table, TheLastRowCountsCorrectLocalizations) {
  ResultTable t;
  t.set("d1", "amcl", 0.1);
  t.set("d2", "amcl", std::nullopt, true);
  t.set("d3", "amcl", 0.2);
  t.set("d1", "s-graph", 0.05);
  t.uncounted = {"s-graph"};
  EXPECT_EQ(formatTable(t, TableFormat::kCsv),
            "world,amcl,s-graph\nd1,0.100,0.050\nd2,✗,\nd3,0.200,\n"
            "localized correctly,2/3,n/a\n");
}

TEST(Table, CsvRoundTrips) {
  const ResultTable t = sample();
  const ResultTable back = parseTableCsv(formatTable(t, TableFormat::kCsv));
  EXPECT_EQ(formatTable(back, TableFormat::kCsv), formatTable(t, TableFormat::kCsv));
  EXPECT_EQ(back.find("d2", "odometry"), nullptr);
  ASSERT_NE(back.find("d2", "is-graphs"), nullptr);
  EXPECT_FALSE(back.find("d2", "is-graphs")->has_value());
}

TEST(Table, NamesWithSeparatorsAreQuotedOrEscaped) {
  ResultTable t;
  t.set("plans/a,b \"x\".json", "is-graphs", 0.5);
  t.set("c|d_e", "is-graphs", 0.25);
  const std::string csv = formatTable(t, TableFormat::kCsv);
  EXPECT_EQ(csv,
            "world,is-graphs\n\"plans/a,b \"\"x\"\".json\",0.500\nc|d_e,0.250\n"
            "localized correctly,2/2\n");
  const ResultTable back = parseTableCsv(csv);
  ASSERT_NE(back.find("plans/a,b \"x\".json", "is-graphs"), nullptr);
  EXPECT_DOUBLE_EQ(**back.find("plans/a,b \"x\".json", "is-graphs"), 0.5);
  EXPECT_NE(formatTable(t, TableFormat::kMarkdown).find("| c\\|d_e | 0.250 |"), std::string::npos);
  EXPECT_NE(formatTable(t, TableFormat::kLatex).find("c|d\\_e & 0.250"), std::string::npos);
}

TEST(Table, BadCsvNamesTheLine) {
  EXPECT_THROW(parseTableCsv(""), std::invalid_argument);
  try {
    parseTableCsv("world,a\nd1,0.1\nd2,fast\n");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "line 3: \"fast\" is neither a number, \"-\" nor \"✗\"");
  }
  try {
    parseTableCsv("world,a,b\nd1,0.1\n");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "line 2: 2 fields, the header has 3");
  }
}

TEST(Table, RegressionsNameTheCell) {
  const ResultTable baseline = parseTableCsv(
      "world,is-graphs,odometry\nd1,0.028,0.099\n"
      "d2,0.030,0.100\nd3,-,0.2\n");
  ResultTable now;
  now.set("d1", "is-graphs", 0.037);         // within 0.01
  now.set("d1", "odometry", 0.120);          // worse by 0.021
  now.set("d2", "is-graphs", std::nullopt);  // failed
  now.set("d2", "odometry", 0.05);           // better
  now.set("d3", "is-graphs", std::nullopt);  // failed, as the baseline
  const auto regressions = findRegressions(baseline, now, 0.01);
  ASSERT_EQ(regressions.size(), 3u);
  EXPECT_EQ(regressions[0].describe(), "d1 / odometry: 0.120 m, baseline 0.099 m");
  EXPECT_EQ(regressions[1].describe(), "d2 / is-graphs: failed (baseline 0.030)");
  EXPECT_EQ(regressions[2].describe(), "d3 / odometry: no run (baseline 0.200)");
}

TEST(Table, WrongLocalizationIsMarkedAndARegression) {
  ResultTable now;
  now.set("d1", "is-graphs", 0.4, true);  // an APE, but wrongly localized on the way
  now.set("d1", "odometry", 0.3);
  EXPECT_EQ(formatTable(now, TableFormat::kCsv),
            "world,is-graphs,odometry\nd1,✗,0.300\nlocalized correctly,0/1,1/1\n");
  EXPECT_NE(formatTable(now, TableFormat::kMarkdown).find("| d1 | ✗ | 0.300 |"), std::string::npos);
  EXPECT_NE(formatTable(now, TableFormat::kLatex).find("d1 & $\\times$ & 0.300"),
            std::string::npos);
  const ResultTable back = parseTableCsv(formatTable(now, TableFormat::kCsv));
  EXPECT_TRUE(back.isWrong("d1", "is-graphs"));
  EXPECT_FALSE(back.isWrong("d1", "odometry"));
  // Against a baseline that localized right: a regression; against one that was wrong too: not.
  const auto regressions = findRegressions(parseTableCsv("world,is-graphs\nd1,0.5\n"), now, 0.01);
  ASSERT_EQ(regressions.size(), 1u);
  EXPECT_EQ(regressions[0].describe(), "d1 / is-graphs: wrongly localized (baseline 0.500)");
  EXPECT_TRUE(findRegressions(back, now, 0.01).empty());
  // A baseline cell that was wrong is not held against a run that now localizes right.
  ResultTable fixed;
  fixed.set("d1", "is-graphs", 0.05);
  fixed.set("d1", "odometry", 0.3);
  EXPECT_TRUE(findRegressions(back, fixed, 0.01).empty());
}

}  // namespace
// Three seeds: 0.02 and 0.04 localized, one wrong. Mean 0.03, sample std sqrt(2e-4) = 0.01414.
TEST(Table, CellStatsOverSeeds) {
  const CellStats s = cellStats({0.02, 0.04, std::nullopt}, {false, false, true});
  EXPECT_EQ(s.runs, 3);
  EXPECT_EQ(s.localized, 2);
  EXPECT_EQ(s.wrong, 1);
  EXPECT_NEAR(*s.mean, 0.03, 1e-12);
  EXPECT_NEAR(*s.std, std::sqrt(2e-4), 1e-12);
  const CellStats one = cellStats({0.5, std::nullopt}, {false, false});
  EXPECT_EQ(one.localized, 1);
  EXPECT_FALSE(one.std.has_value());  // one correct run has no spread
  EXPECT_FALSE(cellStats({std::nullopt}, {false}).mean.has_value());
}

TEST(Table, AggregatedCellsShowMeanStdAndCounts) {
  ResultTable t;
  t.set("d1", "is-graphs", 0.03);
  t.setStats("d1", "is-graphs", cellStats({0.02, 0.04}, {false, false}));
  t.set("d2", "is-graphs", std::nullopt, true);
  t.setStats("d2", "is-graphs", cellStats({0.02, 0.04, 3.0}, {false, false, true}));
  EXPECT_EQ(formatTable(t, TableFormat::kMarkdown),
            "| world | is-graphs |\n|---|---:|\n| d1 | 0.030 ± 0.014 2/2 |\n"
            "| d2 | 0.030 ± 0.014 2/3 1✗ |\n| *localized correctly* | 1/2 |\n");
  const std::string csv = formatTable(t, TableFormat::kCsv);
  EXPECT_EQ(csv,
            "world,is-graphs,is-graphs: std,is-graphs: localized,is-graphs: runs,is-graphs: wrong,"
            "is-graphs: failed,is-graphs: not run\n"
            "d1,0.030,0.014,2,2,0,0,0\nd2,✗,0.014,2,3,1,0,0\nlocalized correctly,1/2,,,,,,\n");
  EXPECT_NE(formatTable(t, TableFormat::kLatex).find("d2 & 0.030 $\\pm$ 0.014 2/3 1$\\times$"),
            std::string::npos);
  // The statistics columns are not methods: a baseline read back has the one column.
  const ResultTable back = parseTableCsv(csv);
  EXPECT_EQ(back.columns, std::vector<std::string>{"is-graphs"});
  EXPECT_NEAR(**back.find("d1", "is-graphs"), 0.03, 1e-12);
  EXPECT_TRUE(back.isWrong("d2", "is-graphs"));
}

TEST(Table, SeedsWithoutAResultAreCountedAndSaid) {
  // A sweep of three seeds where one failed and one has not run: 1/3, never "every seed".
  ResultTable t;
  t.set("d2", "is-graphs", std::nullopt);
  CellStats s = cellStats({0.014, std::nullopt, std::nullopt}, {false, false, false});
  s.failed = 1;
  s.not_run = 1;
  t.setStats("d2", "is-graphs", s);
  EXPECT_EQ(formatTable(t, TableFormat::kMarkdown),
            "| world | is-graphs |\n|---|---:|\n| d2 | 0.014 1/3, 1 failed, 1 not run |\n"
            "| *localized correctly* | 0/1 |\n");
  EXPECT_NE(formatTable(t, TableFormat::kCsv).find("d2,-,,1,3,0,1,1\n"), std::string::npos);
}

TEST(Table, AnyFiniteNumberIsPrintedWhole) {
  ResultTable t;
  t.set("big", "m", 1e30);
  t.set("max", "m", 1.7976931348623157e308);
  const std::string md = formatTable(t, TableFormat::kMarkdown);
  EXPECT_NE(md.find("| big | 1000000000000000019884624838656.000 |"), std::string::npos) << md;
  // 309 digits before the point, all of them.
  const std::size_t at = md.find("| max | ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(md.substr(at + 8, md.find(' ', at + 8) - at - 8).size(), 309u + 4u);
  // The mean of two huge values is finite, not inf.
  const CellStats huge = cellStats({1.5e308, 1.7e308}, {false, false});
  EXPECT_DOUBLE_EQ(*huge.mean, 1.6e308);
  EXPECT_NEAR(*huge.std / 1e307, std::sqrt(2.0), 1e-9);
}

TEST(Table, ABaselineCellMustBeAFiniteNumberAtLeastZero) {
  for (const std::string cell : {"nan", "inf", "-inf", "-0.5", "1e999"}) {
    try {
      parseTableCsv("world,is-graphs\nd1," + cell + "\n");
      ADD_FAILURE() << cell << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    }
  }
}

// What formatTable writes, parseTableCsv reads: a table without methods is a header of "world"
// alone and its count row.
TEST(Table, ATableWithoutMethodsReadsBack) {
  const ResultTable empty;
  const std::string csv = formatTable(empty, TableFormat::kCsv);
  EXPECT_EQ(csv, "world\nlocalized correctly\n");
  const ResultTable back = parseTableCsv(csv);
  EXPECT_TRUE(back.rows.empty());
  EXPECT_TRUE(back.columns.empty());
}

// A control character in a name would be written back as something else (a quoted line break as
// a space): refused, naming the line.
TEST(Table, NamesWithControlCharactersAreRefused) {
  for (const std::string& csv :
       {std::string("world,\"a\rb\"\nd1,0.1\n"), std::string("world,a\nd\x01,0.1\n"),
        std::string("\nworld,a\0\n", 10)}) {
    try {
      parseTableCsv(csv);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("a control character in a field"), std::string::npos)
          << e.what();
    }
  }
  try {
    parseTableCsv("\nnot a header\n");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "line 2: expected a header \"world,<method>,...\"");
  }
}

}  // namespace isg::eval
