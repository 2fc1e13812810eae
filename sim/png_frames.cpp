#include "sim/png_frames.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/input_error.hpp"

namespace isg::sim {

namespace {

// Writes rows of `bytes_per_pixel`-byte pixels of the given PNG colour type and bit depth.
void writeFrame(const std::filesystem::path& path, int width, int height, int colour_type,
                int bit_depth, const unsigned char* pixels, int bytes_per_pixel) {
  FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    throw common::InputError(path.string(), "",
                             std::string("cannot write: ") + std::strerror(errno));
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    throw common::InputError(path.string(), "", "cannot write PNG");
  }
  png_init_io(png, file);
  png_set_compression_level(png, 1);  // zlib's Z_BEST_SPEED
  png_set_IHDR(png, info, width, height, bit_depth, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t stride = std::size_t(width) * bytes_per_pixel;
  for (int y = 0; y < height; ++y) {
    png_write_row(png, const_cast<png_bytep>(pixels + stride * y));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(file) != 0) {
    throw common::InputError(path.string(), "",
                             std::string("cannot write: ") + std::strerror(errno));
  }
}

}  // namespace

void writeRgbFrame(const std::filesystem::path& path, int width, int height,
                   const std::vector<unsigned char>& rgb) {
  writeFrame(path, width, height, PNG_COLOR_TYPE_RGB, 8, rgb.data(), 3);
}

void writeGray16Frame(const std::filesystem::path& path, int width, int height,
                      const std::vector<std::uint16_t>& values) {
  std::vector<unsigned char> big_endian(values.size() * 2);
  for (std::size_t i = 0; i < values.size(); ++i) {
    big_endian[2 * i] = static_cast<unsigned char>(values[i] >> 8);
    big_endian[2 * i + 1] = static_cast<unsigned char>(values[i] & 0xff);
  }
  writeFrame(path, width, height, PNG_COLOR_TYPE_GRAY, 16, big_endian.data(), 2);
}

}  // namespace isg::sim
