#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/occupancy_image.hpp"

namespace isg::formats {

using common::OccupancyImage;
using common::PixelClass;

// A floor plan given as an image (docs/formats.md, "Importing raster floor plans"): PNG (any
// colour type and bit depth) or PGM (P2 and P5, any maxval up to 65535), read into one class per
// pixel as nav2's map_server reads a map's image (common/occupancy_image.hpp). Row 0 is the
// image's top row. libpng is linked here, in formats, and nowhere the localizers link.

// How a pixel's shade becomes a class. The shade is the mean of the pixel's colour channels on a
// scale from 0 (black) to 1 (white); in `kTrinary` mode an alpha channel is averaged in as
// (1 − alpha), as map_server does. `occupancy` is 1 − shade (`negate`: the shade itself).
//   kTrinary: occupied above occupied_thresh, free below free_thresh, else unknown;
//   kScale:   the same, but a pixel that is not fully opaque is unknown;
//   kRaw:     the shade times 255 is the occupancy in per cent (0–100; above: unknown), occupied
//             above occupied_thresh · 100, free below free_thresh · 100.
struct OccupancyRule {
  enum class Mode { kTrinary, kScale, kRaw };
  Mode mode = Mode::kTrinary;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.25;
};

// At most this many pixels (a 120 m × 100 m floor at 1 cm a pixel): one byte each is held.
inline constexpr long long kMaxRasterPixels = 120'000'000;
// The image file itself (compressed): at most this many bytes.
inline constexpr std::uintmax_t kMaxRasterFileBytes = 512ull << 20;

// Called with the image's width and height (pixels) as soon as its header is read, before any
// pixel is decoded or held: the caller's own limits (a plan's extent at its resolution) throw
// there, so that a small file declaring a huge image costs nothing.
using ImageSizeCheck = std::function<void(long long width, long long height)>;

// Reads PATH (PNG by its signature, else PGM by its magic number) and classifies every pixel.
// A file that is neither, is truncated or malformed, or exceeds the limits above: an InputError
// naming the file and what is wrong (with the byte offset for PGM).
OccupancyImage readOccupancyImage(const std::string& path, const OccupancyRule& rule,
                                  const ImageSizeCheck& check_size = {});

// The same from the file's bytes (what readOccupancyImage reads; the fuzzer's entry).
OccupancyImage decodeOccupancyImage(const std::string& bytes, const std::string& file,
                                    const OccupancyRule& rule,
                                    const ImageSizeCheck& check_size = {});

}  // namespace isg::formats
