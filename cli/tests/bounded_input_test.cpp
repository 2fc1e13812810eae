// What a user hands isg by mistake, or receives from someone else, never makes it wait, abort or
// run out of memory (docs/formats.md, "Limits" and "Limits of recordings"): each case is an exact
// error, exit 1 (2 for a malformed option), with nothing written.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

// A FIFO waits for a writer that never comes: opening it would hang, deaf to Ctrl-C. Every
// reader refuses it before it opens it.
TEST(BoundedInput, AFifoIsRefusedBeforeItIsOpened) {
  testing::Sandbox sandbox("bounded_fifo");
  for (const char* name : {"x.mcap", "x.bag", "x.db3", "plan.json"}) {
    ASSERT_EQ(::mkfifo((sandbox.dir() / name).c_str(), 0600), 0);
  }
  std::filesystem::create_directories(sandbox.dir() / "bag2");
  ASSERT_EQ(::mkfifo((sandbox.dir() / "bag2/walk_0.db3").c_str(), 0600), 0);
  const std::string fifo = ": not a regular file but a FIFO (a named pipe): only files are read\n";
  for (const char* recording : {"x.mcap", "x.bag", "x.db3"}) {
    const auto result = sandbox.run(std::string("import ") + recording + " -o out -q");
    EXPECT_EQ(result.exit_code, 1) << recording;
    EXPECT_EQ(result.err, std::string("isg import: error: ") + recording + fifo);
  }
  const auto folder = sandbox.run("import bag2 -o out -q");
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_EQ(folder.err, "isg import: error: bag2/walk_0.db3" + fifo);
  const auto plan = sandbox.run("check plan.json");
  EXPECT_EQ(plan.exit_code, 1);
  EXPECT_EQ(plan.err, "isg check: error: plan.json" + fifo);
  EXPECT_FALSE(sandbox.exists("out"));
}

// Numbers on the command line are decimal and finite: NaN and infinity passed CLI11's range
// check (and reached the tracer as an internal error), "0x10" was sixteen.
TEST(BoundedInput, ARasterImportsNumbersAreDecimalAndInRange) {
  testing::Sandbox sandbox("bounded_numbers");
  sandbox.write("floor.pgm", "P2\n2 2\n255\n0 0\n0 0\n");
  const auto refused = [&](const std::string& options) {
    const auto result = sandbox.run("import floor.pgm " + options + " -o plan.json");
    EXPECT_EQ(result.exit_code, 2) << options;
    EXPECT_FALSE(sandbox.exists("plan.json"));
    return result.err.substr(0, result.err.find('\n'));
  };
  EXPECT_EQ(refused("--resolution 0.01 --origin nan,0"),
            "isg: --origin: expected a number -10000 … 10000, got nan");
  EXPECT_EQ(refused("--resolution 0.01 --origin 0,inf"),
            "isg: --origin: expected a number -10000 … 10000, got inf");
  EXPECT_EQ(refused("--resolution nan"),
            "isg: --resolution: expected a number 0.0001 … 10, got nan");
  EXPECT_EQ(refused("--resolution 0x1"),
            "isg: --resolution: expected a number 0.0001 … 10, got 0x1");
  EXPECT_EQ(refused("--resolution 0.01 --height 1e999"),
            "isg: --height: expected a number 0.1 … 100, got 1e999");
}

std::string bigEndian32(std::uint32_t v) {
  return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG chunk with its CRC-32 (the cli module links no codec: the few lines are here).
std::string pngChunk(const std::string& type, const std::string& data) {
  std::uint32_t crc = 0xffffffffu;
  for (const char byte : type + data) {
    crc ^= std::uint8_t(byte);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return bigEndian32(std::uint32_t(data.size())) + type + data + bigEndian32(~crc);
}

// `bytes` as a zlib stream of one stored (uncompressed) deflate block.
std::string storedZlib(const std::string& bytes) {
  std::uint32_t a = 1, b = 0;  // Adler-32
  for (const char byte : bytes) a = (a + std::uint8_t(byte)) % 65521, b = (b + a) % 65521;
  const auto n = std::uint16_t(bytes.size());
  return std::string{0x78,
                     0x01,
                     0x01,
                     char(n & 0xff),
                     char(n >> 8),
                     char(~n & 0xff),
                     char((~n >> 8) & 0xff)} +
         bytes + bigEndian32((b << 16) | a);
}

// 120 million × 1 pixels is within the pixel limit, but 1.2 million metres at 1 cm: refused on
// the header, before a pixel is decoded (the file holds none: decoding would fail differently).
TEST(BoundedInput, AnImageTooLargeForALevelIsRefusedOnItsHeader) {
  testing::Sandbox sandbox("bounded_png_header");
  const std::string ihdr{0x07, char(0x27), 0x0e, 0x00, 0, 0, 0, 1, 8, 0, 0, 0, 0};  // 120e6 × 1
  const std::string idat = storedZlib(std::string(1001, '\0'));  // the first row's start
  sandbox.write("wide.png", std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) +
                                pngChunk("IDAT", idat) + pngChunk("IEND", ""));
  const auto result = sandbox.run("import wide.png --resolution 0.01 -o plan.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: wide.png: the image (120000000 × 1 pixels) covers 1200000 m × 0 m "
            "at this resolution; a level fits in 1000 m × 1000 m (docs/formats.md, Limits): is "
            "the resolution in metres a pixel?\n");
  EXPECT_FALSE(sandbox.exists("plan.json"));
}

// Messages that name what is wrong: a JPEG is no IFC model; a map's YAML with a byte order mark
// or an empty image.
TEST(BoundedInput, OtherImagesAndOddMapYamlsAreSaidAsTheyAre) {
  testing::Sandbox sandbox("bounded_messages");
  sandbox.write("floor.jpg", "\xFF\xD8\xFF\xE0");
  auto result = sandbox.run("import floor.jpg --resolution 0.01 -o plan.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: floor.jpg: a jpg image: floor plan images are read as PNG or PGM "
            "(convert it losslessly, e.g. `convert FLOOR.jpg FLOOR.png`)\n");
  sandbox.write("floor.pgm", "P2\n2 2\n255\n0 0\n0 0\n");
  sandbox.write("bom.yaml",
                "\xEF\xBB\xBFimage: missing.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.25\nnegate: 0\n");
  result = sandbox.run("import bom.yaml -o plan.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err.rfind("isg import: error: ", 0), 0u);
  EXPECT_NE(result.err.find("missing.pgm"), std::string::npos) << result.err;  // the image read
  sandbox.write("empty.yaml",
                "image: \"\"\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\n"
                "free_thresh: 0.25\nnegate: 0\n");
  result = sandbox.run("import empty.yaml -o plan.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: empty.yaml: /image: line 1: the image is empty: name the map's "
            "PNG or PGM file\n");
  sandbox.write("blank.yaml",
                "image: floor.pgm\nresolution: 0.05\norigin: [, , ]\noccupied_thresh: 0.65\n"
                "free_thresh: 0.25\nnegate: 0\n");
  result = sandbox.run("import blank.yaml -o plan.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: blank.yaml: /origin/0: line 3: \"\" is not a finite number\n");
  EXPECT_FALSE(sandbox.exists("plan.json"));
}

// A dark region thicker than a plan's walls may be is written at the limit, and said.
TEST(BoundedInput, ARegionThickerThanAWallMayBeIsSaid) {
  testing::Sandbox sandbox("bounded_thick");
  const int width = 400, height = 300;  // at 0.1 m: a dark band 30 m × 12 m
  std::string pgm = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      pgm += (c >= 50 && c < 350 && r >= 90 && r < 210) ? '\0' : '\xff';
    }
  }
  sandbox.write("thick.pgm", pgm);
  const auto result = sandbox.run("import thick.pgm --resolution 0.1 -o plan.json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("  W1 is traced 12.00 m thick: a plan's walls and columns are at "
                            "most 10 m, so it is written 10 m thick (a filled area drawn dark?)\n"),
            std::string::npos)
      << result.err;
}

// Options that do nothing where they are given are said, not ignored.
TEST(BoundedInput, ARecordingsOptionWithoutARecordingIsBadUsage) {
  testing::Sandbox sandbox("bounded_unused_options");
  const std::pair<const char*, const char*> cases[] = {
      {"--cloud-layout velodyne",
       "isg: --cloud-layout requires --rosbag or --mcap (it lays out their messages)\n"},
      {"--stamp-offset 5",
       "isg: --stamp-offset requires --rosbag, --mcap or --euroc (it stamps their messages)\n"}};
  for (const auto& [option, message] : cases) {
    const auto result =
        sandbox.run(std::string("simulate builtin:d1 --duration 1 -q -o ds ") + option);
    EXPECT_EQ(result.exit_code, 2) << option;
    EXPECT_EQ(result.err,
              std::string(message) + "Run 'isg --help' (or 'isg COMMAND --help') for usage.\n");
    EXPECT_FALSE(sandbox.exists("ds"));
  }
}

// --euroc renders the scenario's cameras: a scenario without any is refused before anything is
// simulated or written.
TEST(BoundedInput, EurocWithoutCamerasIsRefused) {
  testing::Sandbox sandbox("bounded_euroc_no_cameras");
  const auto result = sandbox.run("simulate builtin:d1 --duration 1 -q -o ds --euroc");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("/cameras: --euroc renders the scenario's cameras, and it has none"),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(sandbox.exists("ds"));
}

}  // namespace
}  // namespace isg::cli
