#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace isg::formats {

// What is wrong with one CDR message, said as "ends inside header.frame_id (byte 13 of 20)": the
// caller names the file, the topic and the message.
struct CdrError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads one message in plain CDR (XCDR1), as ROS 2's rmw implementations write it: a 4-byte
// encapsulation header (0,0 big-endian; 0,1 little-endian), then each primitive aligned to its own
// size counted from the end of that header; strings carry a uint32 count with their terminating
// NUL, sequences a uint32 count of elements. Every length is checked against what is left before
// anything is allocated: a recording is untrusted input.
class CdrReader {
 public:
  explicit CdrReader(std::string_view bytes) : bytes_(bytes) {
    if (bytes_.size() < 4) fail("holds " + std::to_string(bytes_.size()) + " bytes, no CDR header");
    const auto kind = std::uint8_t(bytes_[1]);
    if (bytes_[0] != 0 || kind > 1) {
      fail("encapsulation " + std::to_string(std::uint8_t(bytes_[0])) + "," + std::to_string(kind) +
           " is not plain CDR (0,0 big-endian or 0,1 little-endian)");
    }
    little_ = kind == 1;
    at_ = 4;
  }

  bool littleEndian() const { return little_; }

  std::uint8_t u8(const char* what) {
    need(1, what);
    return std::uint8_t(bytes_[at_++]);
  }
  bool boolean(const char* what) {
    const std::uint8_t v = u8(what);
    if (v > 1) fail(std::string(what) + ": a boolean of " + std::to_string(v));
    return v == 1;
  }
  std::uint16_t u16(const char* what) { return std::uint16_t(unsignedOf(2, what)); }
  std::uint32_t u32(const char* what) { return std::uint32_t(unsignedOf(4, what)); }
  std::int32_t i32(const char* what) { return std::int32_t(u32(what)); }
  std::uint64_t u64(const char* what) { return unsignedOf(8, what); }
  double f64(const char* what) {
    const std::uint64_t bits = u64(what);
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
  }

  // builtin_interfaces/Time {int32 sec, uint32 nanosec} in seconds.
  double time(const char* what) {
    const std::int32_t seconds = i32(what);
    const std::uint32_t nanoseconds = u32(what);
    if (nanoseconds >= 1000000000u) fail(std::string(what) + ": nanoseconds beyond 999999999");
    return seconds + nanoseconds * 1e-9;
  }

  std::string string(const char* what) {
    const std::uint32_t length = u32(what);  // with the terminating NUL
    need(length, what);
    std::string text(bytes_.substr(at_, length == 0 ? 0 : length - 1));
    at_ += length;
    return text;
  }

  // `count` bytes as they are (a uint8[N] array, or the body of a uint8[] sequence).
  std::string_view bytes(std::size_t count, const char* what) {
    need(count, what);
    const std::string_view out = bytes_.substr(at_, count);
    at_ += count;
    return out;
  }

  // A sequence's element count, refused when even `min_element_bytes` per element would not fit
  // in what is left (damage, not memory to allocate).
  std::uint32_t count(std::size_t min_element_bytes, const char* what) {
    const std::uint32_t n = u32(what);
    if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
      fail(std::string(what) + ": " + std::to_string(n) + " elements announced, the message " +
           "holds at most " + std::to_string(remaining() / min_element_bytes));
    }
    return n;
  }

  std::size_t remaining() const { return bytes_.size() - at_; }
  std::size_t position() const { return at_; }

  // A message may end in at most 3 bytes of padding (to 4), no more.
  void expectEnd(const char* after) const {
    if (remaining() > 3) {
      fail(std::to_string(remaining()) + " bytes after " + after + " (byte " + std::to_string(at_) +
           " of " + std::to_string(bytes_.size()) + ")");
    }
  }

  [[noreturn]] void fail(const std::string& reason) const { throw CdrError(reason); }

 private:
  std::uint64_t unsignedOf(std::size_t size, const char* what) {
    align(size);
    need(size, what);
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint64_t byte = std::uint8_t(bytes_[at_ + (little_ ? i : size - 1 - i)]);
      v |= byte << (8 * i);
    }
    at_ += size;
    return v;
  }
  void align(std::size_t n) { at_ = 4 + (at_ - 4 + n - 1) / n * n; }
  void need(std::size_t n, const char* what) const {
    if (at_ > bytes_.size() || bytes_.size() - at_ < n) {
      fail(std::string("ends inside ") + what + " (byte " + std::to_string(at_) + " of " +
           std::to_string(bytes_.size()) + ")");
    }
  }

  std::string_view bytes_;
  bool little_ = true;
  std::size_t at_ = 0;
};

}  // namespace isg::formats
