#include "common/decimal_number.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/tum.hpp"

namespace isg::common {
namespace {

TEST(DecimalNumber, ReadsWhatAPersonWrites) {
  EXPECT_EQ(parseDecimal("1.5"), 1.5);
  EXPECT_EQ(parseDecimal("-2"), -2.0);
  EXPECT_EQ(parseDecimal("+2"), 2.0);
  EXPECT_EQ(parseDecimal(".5"), 0.5);
  EXPECT_EQ(parseDecimal("5."), 5.0);
  EXPECT_EQ(parseDecimal("3e2"), 300.0);
  EXPECT_EQ(parseDecimal("-1.25E-1"), -0.125);
}

// strtod's extras are no numbers on a command line: hexadecimal ("0x10" is not 16), NaN and
// infinity, spaces, a value beyond a double.
TEST(DecimalNumber, RefusesWhatStrtodWouldTake) {
  for (const char* text : {"", "-", ".", "+-1", "0x10", "0X1p3", "nan", "NaN", "inf", "-infinity",
                           " 1", "1 ", "1e", "1e+", "1,5", "1e999", "--1", "1.2.3", "e5"}) {
    EXPECT_FALSE(parseDecimal(text).has_value()) << "'" << text << "'";
  }
}

// A FIFO would hold its reader until a writer comes: it is refused without being opened.
TEST(RegularFile, AFifoIsRefusedUnopened) {
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("isg_fifo_" + std::to_string(::getpid()));
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    checkRegularFile(fifo.string());
    ADD_FAILURE() << "a FIFO passed";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        fifo.string() + ": not a regular file but a FIFO (a named pipe): only files are read");
  }
  std::filesystem::remove(fifo);
}

// A row is never cut at a buffer's end, however long its numbers: each ends with its newline.
TEST(TumText, AHugeNumberKeepsItsRowWhole) {
  StampedPose far;
  far.t = 1.0;
  far.pose = Eigen::Isometry3d::Identity();
  far.pose.translation() = Eigen::Vector3d(1e300, 0.0, 0.0);
  const Trajectory two = {far, far};
  const std::string text = toTumText(two);
  const std::size_t first_newline = text.find('\n');
  ASSERT_NE(first_newline, std::string::npos);
  EXPECT_GT(first_newline, 300u);
  EXPECT_EQ(text.size(), 2 * (first_newline + 1));
  const std::string row_end = " 0.000000000 0.000000000 0.000000000 1.000000000\n";
  EXPECT_EQ(text.substr(first_newline + 1 - row_end.size(), row_end.size()), row_end);
  EXPECT_EQ(text.substr(0, 14), "1.000000000 10");
}

}  // namespace
}  // namespace isg::common
