#include "formats/raster_image.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "formats/map_yaml.hpp"

namespace isg::formats {
namespace {

using Class = PixelClass;

std::string imageErrorOf(const std::string& bytes, const OccupancyRule& rule = {}) {
  try {
    decodeOccupancyImage(bytes, "floor.pgm", rule);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

// An 8-bit PNG in memory, from libpng's own writer.
std::string pngOf(int width, int height, png_uint_32 format, const std::vector<unsigned char>& px) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = format;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, px.data(), 0, nullptr));
  std::string out(size, '\0');
  EXPECT_TRUE(png_image_write_to_memory(&image, out.data(), &size, 0, px.data(), 0, nullptr));
  out.resize(size);
  return out;
}

TEST(RasterImage, AsciiPgmClassifiedByTheThresholds) {
  // Grey 0 (black), 100, 200 and 255 of 255: occupancy 1, 0.61, 0.22, 0 with the default rule
  // (occupied above 0.65, free below 0.25).
  const OccupancyImage image =
      decodeOccupancyImage("P2\n# a comment\n4 1\n255\n0 100 200 255\n", "floor.pgm", {});
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 1);
  EXPECT_EQ(image.at(0, 0), Class::kOccupied);
  EXPECT_EQ(image.at(1, 0), Class::kUnknown);
  EXPECT_EQ(image.at(2, 0), Class::kFree);
  EXPECT_EQ(image.at(3, 0), Class::kFree);
  OccupancyRule negate;
  negate.negate = true;
  const OccupancyImage negated =
      decodeOccupancyImage("P2\n4 1\n255\n0 100 200 255\n", "floor.pgm", negate);
  EXPECT_EQ(negated.at(0, 0), Class::kFree);
  EXPECT_EQ(negated.at(3, 0), Class::kOccupied);
}

TEST(RasterImage, BinaryPgmRowsFromTheTop) {
  const std::string bytes = std::string("P5 2 2 255\n") + char(0) + char(255) + char(255) + char(0);
  const OccupancyImage image = decodeOccupancyImage(bytes, "floor.pgm", {});
  EXPECT_EQ(image.at(0, 0), Class::kOccupied);
  EXPECT_EQ(image.at(1, 0), Class::kFree);
  EXPECT_EQ(image.at(0, 1), Class::kFree);
  EXPECT_EQ(image.at(1, 1), Class::kOccupied);
  // 16-bit samples, big-endian: 0x8000 of 0xffff is a shade of 0.5.
  OccupancyRule half{OccupancyRule::Mode::kTrinary, false, 0.49, 0.3};
  const std::string wide = std::string("P5 1 1 65535\n") + char(0x80) + char(0x00);
  EXPECT_EQ(decodeOccupancyImage(wide, "floor.pgm", half).at(0, 0), Class::kOccupied);
}

TEST(RasterImage, BadImagesSayWhatIsWrong) {
  EXPECT_EQ(imageErrorOf("P5 3 2 255\n" + std::string(4, '\0')),
            "floor.pgm: at byte 11: the raster holds 4 of 6 pixels: the file is truncated");
  EXPECT_EQ(imageErrorOf("P2 2 1 255\n0 300\n"),
            "floor.pgm: at byte 16: a grey value (300) above the maximum 255");
  EXPECT_EQ(imageErrorOf("P2 2 x"),
            "floor.pgm: at byte 5: expected the height (a decimal number), found 'x'");
  EXPECT_EQ(imageErrorOf("P5 0 4 255\n"), "floor.pgm: the image has no pixels (0 × 4)");
  EXPECT_EQ(imageErrorOf("P5 20000 20000 255\n"),
            "floor.pgm: the image has 400000000 pixels (20000 × 20000); at most 120000000 are "
            "read (docs/formats.md, \"Importing raster floor plans\")");
  EXPECT_EQ(imageErrorOf("GIF89a"),
            "floor.pgm: neither a PNG image nor a PGM image (P2 or P5): a floor plan image must "
            "be one of them");
  const std::string png = pngOf(2, 1, PNG_FORMAT_GRAY, {0, 255});
  EXPECT_EQ(imageErrorOf(png.substr(0, 40)).rfind("floor.pgm: not a readable PNG image: ", 0), 0u)
      << imageErrorOf(png.substr(0, 40));
}

TEST(RasterImage, PngChannelsAveragedAsMapServerDoes) {
  // Grey: 0 and 255.
  const OccupancyImage grey =
      decodeOccupancyImage(pngOf(2, 1, PNG_FORMAT_GRAY, {0, 255}), "floor.png", {});
  EXPECT_EQ(grey.at(0, 0), Class::kOccupied);
  EXPECT_EQ(grey.at(1, 0), Class::kFree);
  // Colour: the mean of the channels (red alone, 255/3 of 255: occupancy 0.67: occupied).
  const OccupancyImage colour =
      decodeOccupancyImage(pngOf(1, 1, PNG_FORMAT_RGB, {255, 0, 0}), "floor.png", {});
  EXPECT_EQ(colour.at(0, 0), Class::kOccupied);
  // Grey with alpha, trinary: alpha is averaged in as a fourth channel. Black opaque: shade
  // (0 + 0 + 0 + 1) / 4 = 0.25, occupancy 0.75: occupied; white transparent: shade 0.75,
  // occupancy 0.25: not below free_thresh 0.25, so unknown.
  const std::string ga = pngOf(2, 1, PNG_FORMAT_GA, {0, 255, 255, 0});
  const OccupancyImage trinary = decodeOccupancyImage(ga, "floor.png", {});
  EXPECT_EQ(trinary.at(0, 0), Class::kOccupied);
  EXPECT_EQ(trinary.at(1, 0), Class::kUnknown);
  // Scale: a pixel not fully opaque is unknown; the opaque one is read from its colour alone.
  OccupancyRule scale;
  scale.mode = OccupancyRule::Mode::kScale;
  const OccupancyImage scaled = decodeOccupancyImage(ga, "floor.png", scale);
  EXPECT_EQ(scaled.at(0, 0), Class::kOccupied);
  EXPECT_EQ(scaled.at(1, 0), Class::kUnknown);
  // Raw: the grey value is the occupancy in per cent; above 100, unknown.
  OccupancyRule raw;
  raw.mode = OccupancyRule::Mode::kRaw;
  const OccupancyImage raws =
      decodeOccupancyImage(pngOf(3, 1, PNG_FORMAT_GRAY, {100, 10, 200}), "floor.png", raw);
  EXPECT_EQ(raws.at(0, 0), Class::kOccupied);
  EXPECT_EQ(raws.at(1, 0), Class::kFree);
  EXPECT_EQ(raws.at(2, 0), Class::kUnknown);
}

// A PNG of `depth` bits a sample (grey, or palette indices when `palette` is given), written with
// libpng's full interface: the simplified one writes 8 bits only. Samples row by row from the top.
std::string packedPngOf(int width, int height, int depth, const std::vector<png_color>& palette,
                        const std::vector<unsigned char>& samples) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(data), n);
      },
      nullptr);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), depth,
               palette.empty() ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  png_set_check_for_invalid_index(png, 0);  // the bad palette index below is written as asked
  png_set_compression_level(png, 9);
  png_write_info(png, info);
  png_set_packing(png);  // one sample a byte in, `depth` bits a sample out
  std::vector<unsigned char> row(static_cast<std::size_t>(width));
  for (int r = 0; r < height; ++r) {
    std::copy_n(samples.begin() + std::ptrdiff_t(r) * width, width, row.begin());
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

// Plans drawn at 1, 2 or 4 bits compress far better than at 8: they were refused as truncated,
// judged on their rows widened to bytes. Each decodes as the same plan at 8 bits does; an index
// past the palette is an error naming the pixel, not a black one.
TEST(RasterImage, LowBitDepthAndPalettePngsReadAsTheirEightBitPlan) {
  const int width = 2000, height = 2000;  // a dark frame 10 px wide round a light floor
  const auto dark = [&](int c, int r) {
    return c < 10 || r < 10 || c >= width - 10 || r >= height - 10;
  };
  std::vector<unsigned char> grey8(std::size_t(width) * height);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) grey8[std::size_t(r) * width + c] = dark(c, r) ? 0 : 255;
  }
  const OccupancyImage expected =
      decodeOccupancyImage(pngOf(width, height, PNG_FORMAT_GRAY, grey8), "floor.png", {});
  const std::vector<png_color> black_white = {{0, 0, 0}, {255, 255, 255}};
  for (const int depth : {1, 2, 4}) {
    std::vector<unsigned char> grey(grey8.size()), index(grey8.size());
    for (std::size_t k = 0; k < grey8.size(); ++k) {
      grey[k] = grey8[k] ? (1 << depth) - 1 : 0;
      index[k] = grey8[k] ? 1 : 0;
    }
    const std::string grey_png = packedPngOf(width, height, depth, {}, grey);
    const std::string palette_png = packedPngOf(width, height, depth, black_white, index);
    EXPECT_LT(grey_png.size(), 5000u);  // compressed past what an 8-bit row could be
    EXPECT_EQ(decodeOccupancyImage(grey_png, "floor.png", {}).pixels, expected.pixels) << depth;
    EXPECT_EQ(decodeOccupancyImage(palette_png, "floor.png", {}).pixels, expected.pixels) << depth;
  }
  std::vector<unsigned char> beyond = {1, 0, 1, 5, 0, 1};  // index 5 of a palette of 2
  const std::string bad = packedPngOf(3, 2, 8, black_white, beyond);
  const std::string error = imageErrorOf(bad);
  EXPECT_EQ(error.substr(0, error.find(" (near byte")),
            "floor.pgm: not a readable PNG image: the pixel at column 0, row 1 has palette index "
            "5; the palette holds 2 colours");
}

// The caller's size check sees the header's width and height before any pixel is decoded: a
// small file declaring a huge image costs nothing.
TEST(RasterImage, TheCallersSizeCheckRunsOnTheHeader) {
  const auto refuseAll = [](long long width, long long height) {
    throw common::InputError("floor.png", "",
                             std::to_string(width) + " × " + std::to_string(height));
  };
  std::vector<unsigned char> grey(12, 0);
  for (const std::string& image :
       {pngOf(4, 3, PNG_FORMAT_GRAY, grey), std::string("P5 4 3 255\n") + std::string(12, '\0')}) {
    try {
      decodeOccupancyImage(image, "floor.png", {}, refuseAll);
      ADD_FAILURE() << "decoded";
    } catch (const common::InputError& e) {
      EXPECT_EQ(std::string(e.what()), "floor.png: 4 × 3");
    }
  }
}

std::string yamlError(const std::string& text) {
  try {
    parseMapYaml(text, "/maps/lab.yaml");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MapYaml, ReadsMapServersFields) {
  const MapYaml map = parseMapYaml(
      "image: lab.pgm   # the occupancy\nresolution: 0.050000\norigin: [-12.5, 3.0, 0.1]\n"
      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n",
      "/maps/lab.yaml");
  EXPECT_EQ(map.image, "/maps/lab.pgm");
  EXPECT_DOUBLE_EQ(map.resolution, 0.05);
  EXPECT_DOUBLE_EQ(map.origin_x, -12.5);
  EXPECT_DOUBLE_EQ(map.origin_y, 3.0);
  EXPECT_DOUBLE_EQ(map.origin_yaw, 0.1);
  EXPECT_FALSE(map.rule.negate);
  EXPECT_DOUBLE_EQ(map.rule.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(map.rule.free_thresh, 0.196);
  EXPECT_EQ(map.rule.mode, OccupancyRule::Mode::kScale);
  const MapYaml absolute = parseMapYaml(
      "image: \"/data/floor.png\"\nresolution: 0.01\norigin: [0, 0, 0]\nnegate: true\n"
      "occupied_thresh: 0.5\nfree_thresh: 0.5\n",
      "lab.yaml");
  EXPECT_EQ(absolute.image, "/data/floor.png");
  EXPECT_TRUE(absolute.rule.negate);
  EXPECT_EQ(absolute.rule.mode, OccupancyRule::Mode::kTrinary);
}

TEST(MapYaml, BadFieldsNameTheKeyAndTheLine) {
  const std::string good_tail = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n";
  EXPECT_EQ(yamlError("image: a.pgm\nresolution: 0.05\n" + good_tail),
            "/maps/lab.yaml: /origin: missing: a map's YAML names its image, resolution, origin, "
            "negate, occupied_thresh and free_thresh (as map_server requires)");
  EXPECT_EQ(yamlError("image: a.pgm\nresolution: 0.05\norigin: [1, 2]\n" + good_tail),
            "/maps/lab.yaml: /origin: line 3: the origin has 3 elements, [x, y, yaw], not 2");
  EXPECT_EQ(yamlError("image: a.pgm\nresolution: fine\norigin: [1, 2, 0]\n" + good_tail),
            "/maps/lab.yaml: /resolution: line 2: \"fine\" is not a finite number");
  EXPECT_EQ(yamlError("image: a.pgm\nresolution: 0.05\norigin: [1, 2, 0]\n" + good_tail +
                      "mode: fuzzy\n"),
            "/maps/lab.yaml: /mode: line 7: expected trinary, scale or raw, found \"fuzzy\"");
  EXPECT_EQ(yamlError("image: a.pgm\nresolution: 0.05\norigin: [1, 2, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.2\nfree_thresh: 0.25\n"),
            "/maps/lab.yaml: /free_thresh: line 6: above occupied_thresh: no pixel could be both");
}

}  // namespace
}  // namespace isg::formats
