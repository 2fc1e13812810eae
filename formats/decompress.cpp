#include "formats/decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>

namespace isg::formats {

namespace {

// The output grown by doubling (from 4 kB) up to `limit` bytes; false when it is full already
// (the data goes on past what the record says it holds).
bool grow(std::string& out, std::uint64_t limit) {
  if (out.size() == limit) return false;
  out.resize(std::min<std::size_t>(limit, std::max<std::size_t>(4096, 2 * out.size())));
  return true;
}

// Each codec decompresses into `out` and returns the bytes written, or sets `error`.
std::size_t bzip2(std::string_view stored, std::uint64_t size, std::string& out,
                  std::string& error) {
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) {
    error = "cannot start bzip2";
    return 0;
  }
  stream.next_in = const_cast<char*>(stored.data());  // bzip2 only reads it
  stream.avail_in = unsigned(stored.size());
  std::size_t written = 0;
  bool too_long = false;  // the output is full and the data goes on
  int status = BZ_OK;
  while (status == BZ_OK) {
    if (written == out.size() && !grow(out, size)) {
      too_long = true;
      break;
    }
    stream.next_out = out.data() + written;
    stream.avail_out = unsigned(out.size() - written);
    status = BZ2_bzDecompress(&stream);
    written = out.size() - stream.avail_out;
    if (status == BZ_OK && stream.avail_in == 0 && stream.avail_out > 0) break;  // cut short
  }
  BZ2_bzDecompressEnd(&stream);
  if (too_long) {
    error = "it holds more";
  } else if (status != BZ_STREAM_END) {
    error = "bzip2 status " + std::to_string(status);
  }
  return written;
}

std::size_t zstd(std::string_view stored, std::uint64_t size, std::string& out,
                 std::string& error) {
  ZSTD_DStream* stream = ZSTD_createDStream();
  if (stream == nullptr || ZSTD_isError(ZSTD_initDStream(stream))) {
    if (stream != nullptr) ZSTD_freeDStream(stream);
    error = "cannot start zstd";
    return 0;
  }
  ZSTD_inBuffer in{stored.data(), stored.size(), 0};
  std::size_t written = 0;
  bool too_long = false;
  std::size_t status = 1;  // 0 once a frame is complete (frames may follow one another)
  // One byte of room past `size`: a frame may still have its epilogue to read when its last
  // byte is out, and only more output than `size` says that it holds more.
  const std::uint64_t room = size + 1;
  while (status != 0 || in.pos < in.size) {
    if (written == out.size() && !grow(out, room)) {
      too_long = true;
      break;
    }
    ZSTD_outBuffer sink{out.data(), out.size(), written};
    const std::size_t before_in = in.pos;
    status = ZSTD_decompressStream(stream, &sink, &in);
    if (ZSTD_isError(status)) break;
    const bool progress = sink.pos > written || in.pos > before_in;
    written = sink.pos;
    if (!progress) break;  // cut short
  }
  ZSTD_freeDStream(stream);
  if (too_long) {
    error = "it holds more";
  } else if (ZSTD_isError(status)) {
    error = ZSTD_getErrorName(status);
  } else if (status != 0) {
    error = "the zstd frame does not end";
  }
  return written;
}

std::size_t lz4(std::string_view stored, std::uint64_t size, std::string& out, std::string& error) {
  LZ4F_dctx* context = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
    error = "cannot start LZ4";
    return 0;
  }
  std::size_t written = 0, read = 0, status = 1;
  bool too_long = false;
  while (status != 0 && read < stored.size()) {
    if (written == out.size() && !grow(out, size)) {
      too_long = true;
      break;
    }
    std::size_t out_size = out.size() - written, in_size = stored.size() - read;
    status = LZ4F_decompress(context, out.data() + written, &out_size, stored.data() + read,
                             &in_size, nullptr);
    if (LZ4F_isError(status)) break;
    written += out_size;
    read += in_size;
    if (out_size == 0 && in_size == 0 && written < out.size()) break;  // no progress
  }
  LZ4F_freeDecompressionContext(context);
  if (too_long) {
    error = "it holds more";
  } else if (LZ4F_isError(status)) {
    error = LZ4F_getErrorName(status);
  } else if (status != 0) {
    error = "the LZ4 frame does not end";
  }
  return written;
}

}  // namespace

bool decompress(const std::string& compression, std::string_view stored, std::uint64_t size,
                std::string& out, std::string& error) {
  out.clear();
  error.clear();
  const std::size_t written = compression == "bz2"    ? bzip2(stored, size, out, error)
                              : compression == "zstd" ? zstd(stored, size, out, error)
                                                      : lz4(stored, size, out, error);
  if (!error.empty()) return false;
  if (written != size) {
    error = "it holds " + std::to_string(written);
    return false;
  }
  out.resize(written);
  return true;
}

}  // namespace isg::formats
