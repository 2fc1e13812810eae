// The size rule of docs/architecture.md ("Function length") holds for the whole tree, and its
// checker finds a long function and a stale allow-list entry, naming file, line and length.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "function_length_rules.hpp"

namespace isg::architecture {
namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const auto& l : lines) all += l + "\n";
  return all;
}

TEST(FunctionLength, NoFunctionOfTheSourcesIsOverTheLimitButThoseAllowedAndWhy) {
  const std::vector<std::string> files = sourcesUnderRule(ISG_SOURCE_DIR);
  ASSERT_GT(files.size(), 300u);  // the modules were found
  const auto extents = functionExtents(ISG_SOURCE_DIR, files, ISG_CTAGS);
  ASSERT_GT(extents.size(), 2000u);  // ctags read them
  const auto breaches = checkFunctionLengths(extents, allowedLongFunctions());
  EXPECT_TRUE(breaches.empty()) << joined(breaches);
  for (const auto& allowed : allowedLongFunctions()) EXPECT_GT(allowed.why.size(), 40u);
}

// A function body of `lines` lines in all, from its signature to its closing brace.
std::string functionOf(const std::string& name, int lines) {
  std::string text = "int " + name + "(int x) {\n";
  for (int i = 0; i < lines - 3; ++i) text += "  x += " + std::to_string(i) + ";\n";
  return text + "  return x;\n}\n";
}

class FunctionLengthChecker : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("isg_length_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    write("bim/short.cpp", functionOf("shortEnough", 100));
    write("bim/tests/long_test.cpp", functionOf("aLongTest", 300));  // tests are not held to it
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& file, const std::string& text) {
    fs::create_directories((root_ / file).parent_path());
    std::ofstream(root_ / file) << text;
  }
  std::vector<std::string> breaches(const std::vector<LongFunction>& allowed) {
    return checkFunctionLengths(functionExtents(root_, sourcesUnderRule(root_), ISG_CTAGS),
                                allowed);
  }
  fs::path root_;
};

TEST_F(FunctionLengthChecker, AHundredLinesPassTestsAreNotHeldToIt) {
  EXPECT_TRUE(breaches({}).empty()) << joined(breaches({}));
}

TEST_F(FunctionLengthChecker, AFunctionOfOneHundredAndOneLinesIsNamedWithFileLineAndLength) {
  write("worlds/long.cpp", "// one line before\n" + functionOf("tooLong", 101));
  EXPECT_EQ(breaches({}),
            std::vector<std::string>{
                "worlds/long.cpp:2: tooLong is 101 lines, over 100: split it into named steps "
                "(docs/architecture.md, \"Function length\")"});
}

TEST_F(FunctionLengthChecker, AnAllowedFunctionPassesUpToTheHardLimitOnly) {
  write("worlds/long.cpp", functionOf("optionTable", 150));
  EXPECT_TRUE(breaches({{"worlds/long.cpp", "optionTable", "an option table"}}).empty());
  write("worlds/long.cpp", functionOf("optionTable", 151));
  EXPECT_EQ(breaches({{"worlds/long.cpp", "optionTable", "an option table"}}),
            std::vector<std::string>{"worlds/long.cpp:1: optionTable is 151 lines, over 150 even "
                                     "on the allow-list: split it"});
}

TEST_F(FunctionLengthChecker, AnAllowListEntryThatIsNoLongerLongMustGo) {
  EXPECT_EQ(breaches({{"bim/short.cpp", "shortEnough", "was long once"}}),
            std::vector<std::string>{
                "bim/short.cpp: shortEnough is on the allow-list but no longer over 100 lines (or "
                "gone): take it off (cli/tests/function_length_rules.hpp)"});
}

}  // namespace
}  // namespace isg::architecture
