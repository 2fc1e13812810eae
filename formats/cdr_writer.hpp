#pragma once

#include <bit>
#include <cstdint>
#include <string>

namespace isg::formats {

// Serialises one message in CDR as ROS 2 writes it (little endian, plain CDR): a 4-byte
// encapsulation header (0x00 0x01 0x00 0x00), then each primitive aligned to its own size,
// counted from the end of that header; strings and sequences carry a uint32 count first (a
// string's counts its terminating NUL).
class CdrWriter {
  static_assert(std::endian::native == std::endian::little,
                "CDR here is written as the host lays it");

 public:
  CdrWriter() : bytes_("\x00\x01\x00\x00", 4) {}

  void u8(std::uint8_t v) { put(&v, 1); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void u16(std::uint16_t v) { put(&v, 2); }
  void i32(std::int32_t v) { put(&v, 4); }
  void u32(std::uint32_t v) { put(&v, 4); }
  void f64(double v) { put(&v, 8); }
  void string(const std::string& s) {
    u32(std::uint32_t(s.size() + 1));
    bytes_.append(s);
    bytes_.push_back('\0');
  }
  // A uint8[] sequence: its count, then the bytes as they are.
  void bytes(const std::string& data) {
    u32(std::uint32_t(data.size()));
    bytes_.append(data);
  }

  const std::string& data() const { return bytes_; }

 private:
  void put(const void* v, std::size_t size) {
    const std::size_t body = bytes_.size() - 4;
    bytes_.append((size - body % size) % size, '\0');
    bytes_.append(static_cast<const char*>(v), size);
  }
  std::string bytes_;
};

}  // namespace isg::formats
