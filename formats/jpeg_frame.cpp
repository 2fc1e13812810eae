#include "formats/jpeg_frame.hpp"

// libjpeg's header needs size_t and FILE declared before it.
#include <jpeglib.h>
#include <png.h>
#include <cstddef>
#include <cstdio>

#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "common/input_error.hpp"
#include "formats/frame_size.hpp"

namespace isg::formats {

namespace {

// libpng's simplified reader: an 8-bit RGB file is read as it is (no gamma change).
std::vector<unsigned char> readRgbPng(const std::string& path, int& width, int& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    throw common::InputError(path, "", std::string("not a PNG image: ") + image.message);
  }
  if (image.format != PNG_FORMAT_RGB) {
    png_image_free(&image);
    throw common::InputError(path, "", "not an 8-bit RGB image");
  }
  std::vector<unsigned char> rgb(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr)) {
    throw common::InputError(path, "", std::string("cannot be decoded: ") + image.message);
  }
  width = int(image.width);
  height = int(image.height);
  return rgb;
}

// libjpeg's error manager with where to jump, and the output buffer (kept in memory, not in a
// register, across the jump).
struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
};

void jpegFailure(j_common_ptr info) {
  std::longjmp(reinterpret_cast<JpegError*>(info->err)->jump, 1);
}

}  // namespace

std::string rgbPngFileToJpeg(const std::string& png_path, int expected_width, int expected_height,
                             int quality) {
  int width = 0, height = 0;
  const std::vector<unsigned char> rgb = readRgbPng(png_path, width, height);
  requireFrameSize(png_path, width, height, expected_width, expected_height);
  jpeg_compress_struct info;
  JpegError error;
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = jpegFailure;
  // Nothing with a destructor lives between here and the longjmp target.
  if (setjmp(error.jump)) {
    jpeg_destroy_compress(&info);
    std::free(error.buffer);
    throw common::InputError(png_path, "", "could not be encoded as JPEG");
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &error.buffer, &error.size);
  info.image_width = JDIMENSION(width);
  info.image_height = JDIMENSION(height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb.data() + std::size_t(info.next_scanline) * width * 3);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::string out(reinterpret_cast<const char*>(error.buffer), error.size);
  std::free(error.buffer);
  return out;
}

}  // namespace isg::formats
