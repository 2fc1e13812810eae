#include "formats/raster_image.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstring>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {
namespace {

std::string bytes(long long n) { return std::to_string(n); }

void checkSize(long long width, long long height, const std::string& file) {
  if (width <= 0 || height <= 0) {
    throw common::InputError(
        file, "", "the image has no pixels (" + bytes(width) + " × " + bytes(height) + ")");
  }
  if (width * height > kMaxRasterPixels) {
    throw common::InputError(file, "",
                             "the image has " + bytes(width * height) + " pixels (" + bytes(width) +
                                 " × " + bytes(height) + "); at most " + bytes(kMaxRasterPixels) +
                                 " are read (docs/formats.md, \"Importing raster floor plans\")");
  }
}

// A pixel's class from its colour channels and alpha on [0, 1] (alpha 1 when the image has none).
PixelClass classifyPixel(double mean_colour, double alpha, bool has_alpha,
                         const OccupancyRule& rule) {
  using Mode = OccupancyRule::Mode;
  if (rule.mode == Mode::kRaw) {
    const double percent = std::round(mean_colour * 255.0);
    if (percent > 100.0) return PixelClass::kUnknown;
    if (percent > rule.occupied_thresh * 100.0) return PixelClass::kOccupied;
    if (percent < rule.free_thresh * 100.0) return PixelClass::kFree;
    return PixelClass::kUnknown;
  }
  double shade = mean_colour;
  if (rule.mode == Mode::kTrinary && has_alpha) {
    shade = (3.0 * mean_colour + alpha) / 4.0;  // map_server averages the alpha in as a channel
  }
  if (rule.mode == Mode::kScale && has_alpha && alpha < 1.0) return PixelClass::kUnknown;
  const double occupancy = rule.negate ? shade : 1.0 - shade;
  if (occupancy > rule.occupied_thresh) return PixelClass::kOccupied;
  if (occupancy < rule.free_thresh) return PixelClass::kFree;
  return PixelClass::kUnknown;
}

// ---- PGM (Netpbm P2 / P5) ----

struct PgmReader {
  const std::string& text;
  const std::string& file;
  std::size_t at = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw common::InputError(file, "", "at byte " + std::to_string(at) + ": " + what);
  }
  void skipSpaceAndComments() {
    while (at < text.size()) {
      const char c = text[at];
      if (c == '#') {
        while (at < text.size() && text[at] != '\n') ++at;
      } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
        ++at;
      } else {
        break;
      }
    }
  }
  long long number(const char* what) {
    skipSpaceAndComments();
    if (at >= text.size()) fail(std::string("the file ends before its ") + what);
    if (text[at] < '0' || text[at] > '9') {
      fail(std::string("expected the ") + what + " (a decimal number), found '" +
           std::string(1, text[at]) + "'");
    }
    long long value = 0;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9') {
      value = value * 10 + (text[at] - '0');
      if (value > 1'000'000'000) fail(std::string("the ") + what + " is too large");
      ++at;
    }
    return value;
  }
};

OccupancyImage decodePgm(const std::string& text, const std::string& file,
                         const OccupancyRule& rule, const ImageSizeCheck& check_size) {
  PgmReader in{text, file};
  const bool binary = text[1] == '5';
  in.at = 2;
  const long long width = in.number("width");
  const long long height = in.number("height");
  const long long maxval = in.number("maximum grey value");
  if (maxval < 1 || maxval > 65535) in.fail("the maximum grey value must be 1–65535");
  checkSize(width, height, file);
  if (check_size) check_size(width, height);
  const std::size_t count = std::size_t(width * height);
  const std::size_t sample = maxval < 256 ? 1 : 2;
  // The raster's length is checked before anything is held for it.
  if (binary) {
    // One whitespace character after maxval, then the raster.
    if (in.at >= text.size()) in.fail("the file ends before its raster");
    ++in.at;
    if (text.size() - in.at < count * sample) {
      in.fail("the raster holds " + std::to_string((text.size() - in.at) / sample) + " of " +
              std::to_string(count) + " pixels: the file is truncated");
    }
  } else if ((text.size() - in.at + 1) / 2 < count) {
    in.fail("the file is too short for " + std::to_string(count) + " grey values: it is truncated");
  }
  OccupancyImage image;
  image.width = int(width);
  image.height = int(height);
  image.pixels.resize(count);
  if (binary) {
    const auto* p = reinterpret_cast<const unsigned char*>(text.data() + in.at);
    for (std::size_t i = 0; i < count; ++i) {
      const long long v =
          sample == 1 ? p[i] : (static_cast<long long>(p[2 * i]) << 8) | p[2 * i + 1];
      if (v > maxval) {
        in.at += i * sample;
        in.fail("a grey value (" + std::to_string(v) + ") above the maximum " +
                std::to_string(maxval));
      }
      image.pixels[i] = classifyPixel(double(v) / double(maxval), 1.0, false, rule);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      const long long v = in.number("grey value");
      if (v > maxval) {
        in.fail("a grey value (" + std::to_string(v) + ") above the maximum " +
                std::to_string(maxval));
      }
      image.pixels[i] = classifyPixel(double(v) / double(maxval), 1.0, false, rule);
    }
  }
  return image;
}

// ---- PNG (libpng, row by row: one row of 8-bit channels held, never the whole image) ----

struct PngSource {
  const std::string* bytes;
  std::size_t at = 8;  // the signature is checked before
};

struct PngError {
  std::jmp_buf jump;
  char message[256] = {};
};

void readPngBytes(png_structp png, png_bytep out, png_size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (source->bytes->size() - source->at < length) {
    png_error(png, "the file is truncated");
  }
  std::memcpy(out, source->bytes->data() + source->at, length);
  source->at += length;
}

void pngFailure(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof error->message, "%s", message);
  std::longjmp(error->jump, 1);
}

void pngWarning(png_structp, png_const_charp) {}  // ancillary chunks' complaints: not ours

struct PngHandles {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngHandles() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

// A palette image's colours classed once each (the tRNS alpha with them); its palette's size.
// Called between setjmp and the end: it owns nothing a longjmp could skip.
int paletteClasses(png_structp png, png_infop info, const OccupancyRule& rule,
                   std::array<PixelClass, 256>& palette_class) {
  png_colorp palette = nullptr;
  int palette_size = 0;
  if (png_get_PLTE(png, info, &palette, &palette_size) != PNG_INFO_PLTE) {
    png_error(png, "a palette image without its palette (PLTE)");
  }
  png_bytep trans = nullptr;
  int trans_count = 0;
  png_get_tRNS(png, info, &trans, &trans_count, nullptr);
  const bool has_alpha = trans != nullptr && trans_count > 0;
  for (int k = 0; k < palette_size; ++k) {
    const double mean = (palette[k].red + palette[k].green + palette[k].blue) / 3.0 / 255.0;
    const double alpha = has_alpha && k < trans_count ? trans[k] / 255.0 : 1.0;
    palette_class[std::size_t(k)] = classifyPixel(mean, alpha, has_alpha, rule);
  }
  return palette_size;
}

// Everything between setjmp and the end lives in `image` and `row`, owned outside, so that a
// longjmp out of libpng skips no destructor.
bool decodePngRows(PngHandles& handles, PngError& error, PngSource& source, const std::string& file,
                   const OccupancyRule& rule, const ImageSizeCheck& check_size,
                   OccupancyImage& image, std::vector<unsigned char>& row,
                   std::vector<unsigned char>& whole, std::vector<png_bytep>& rows) {
  if (setjmp(error.jump)) return false;
  png_structp png = handles.png;
  png_infop info = handles.info;
  png_set_read_fn(png, &source, readPngBytes);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);
  png_read_info(png, info);
  const long long width = png_get_image_width(png, info);
  const long long height = png_get_image_height(png, info);
  checkSize(width, height, file);  // throws: nothing of libpng's is live here but the handles
  if (check_size) check_size(width, height);  // so may the caller's check
  // Deflate packs at most about 1032 bytes into one: a file far shorter than its rows could be is
  // truncated, and is refused before its pixels are held. The rows as stored count here (before
  // 1-, 2- and 4-bit samples are widened to bytes): a well-compressed 1-bit plan is no truncated
  // 8-bit one.
  const double stored_stride = double(png_get_rowbytes(png, info));
  if ((stored_stride + 1.0) * double(height) > 1032.0 * double(source.bytes->size()) + 4096.0) {
    png_error(png, "the file is far too short for its image: truncated");
  }
  const int colour = png_get_color_type(png, info);
  const bool indexed = colour == PNG_COLOR_TYPE_PALETTE;
  // A palette image is read as its indices (one byte each), each checked against the palette and
  // classed by its colour: libpng's own expansion reads an index past the palette as black.
  std::array<PixelClass, 256> palette_class{};
  int palette_size = 0;
  if (indexed) {
    palette_size = paletteClasses(png, info, rule, palette_class);
    png_set_packing(png);
  } else {
    if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) {
      png_set_expand_gray_1_2_4_to_8(png);
    }
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    png_set_strip_16(png);
  }
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const bool has_alpha = channels == 2 || channels == 4;
  const int colours = has_alpha ? channels - 1 : channels;
  const std::size_t stride = png_get_rowbytes(png, info);
  image.width = int(width);
  image.height = int(height);
  image.pixels.resize(std::size_t(width * height));
  auto classifyRow = [&](const unsigned char* p, int r) {
    if (indexed) {
      for (long long c = 0; c < width; ++c) {
        if (p[c] >= palette_size) {
          std::snprintf(error.message, sizeof error.message,
                        "the pixel at column %lld, row %d has palette index %d; the palette holds "
                        "%d colours",
                        c, r, int(p[c]), palette_size);
          return false;
        }
        image.pixels[std::size_t(r) * width + c] = palette_class[p[c]];
      }
      return true;
    }
    for (long long c = 0; c < width; ++c, p += channels) {
      double sum = 0.0;
      for (int k = 0; k < colours; ++k) sum += p[k];
      const double mean = sum / double(colours) / 255.0;
      const double alpha = has_alpha ? p[channels - 1] / 255.0 : 1.0;
      image.pixels[std::size_t(r) * width + c] = classifyPixel(mean, alpha, has_alpha, rule);
    }
    return true;
  };
  if (passes == 1) {
    row.resize(stride);
    for (long long r = 0; r < height; ++r) {
      png_read_row(png, row.data(), nullptr);
      if (!classifyRow(row.data(), int(r))) return false;
    }
  } else {
    // Interlaced: the passes fill the whole image before any row is final.
    whole.resize(stride * std::size_t(height));
    rows.resize(static_cast<std::size_t>(height));
    for (long long r = 0; r < height; ++r) rows[r] = whole.data() + stride * r;
    png_read_image(png, rows.data());
    for (long long r = 0; r < height; ++r) {
      if (!classifyRow(rows[r], int(r))) return false;
    }
  }
  return true;
}

OccupancyImage decodePng(const std::string& bytes_in, const std::string& file,
                         const OccupancyRule& rule, const ImageSizeCheck& check_size) {
  PngError error;
  PngHandles handles;
  handles.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, pngFailure, pngWarning);
  if (handles.png == nullptr) throw common::InputError(file, "", "libpng could not start");
  handles.info = png_create_info_struct(handles.png);
  if (handles.info == nullptr) throw common::InputError(file, "", "libpng could not start");
  PngSource source{&bytes_in};
  OccupancyImage image;
  std::vector<unsigned char> row, whole;
  std::vector<png_bytep> rows;
  if (!decodePngRows(handles, error, source, file, rule, check_size, image, row, whole, rows)) {
    throw common::InputError(file, "",
                             std::string("not a readable PNG image: ") + error.message +
                                 " (near byte " + std::to_string(source.at) + ")");
  }
  return image;
}

}  // namespace

OccupancyImage decodeOccupancyImage(const std::string& bytes_in, const std::string& file,
                                    const OccupancyRule& rule, const ImageSizeCheck& check_size) {
  static constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes_in.size() >= 8 && std::memcmp(bytes_in.data(), kPngSignature, 8) == 0) {
    return decodePng(bytes_in, file, rule, check_size);
  }
  if (bytes_in.size() >= 2 && bytes_in[0] == 'P' && (bytes_in[1] == '2' || bytes_in[1] == '5')) {
    return decodePgm(bytes_in, file, rule, check_size);
  }
  throw common::InputError(file, "",
                           "neither a PNG image nor a PGM image (P2 or P5): a floor plan image "
                           "must be one of them");
}

OccupancyImage readOccupancyImage(const std::string& path, const OccupancyRule& rule,
                                  const ImageSizeCheck& check_size) {
  return decodeOccupancyImage(common::readCheckedFile(path, kMaxRasterFileBytes), path, rule,
                              check_size);
}

}  // namespace isg::formats
