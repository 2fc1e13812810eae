#include "formats/velodyne_scan_cdr.hpp"

#include <cstdint>
#include <cstring>

#include "common/input_error.hpp"
#include "formats/vlp16_packet.hpp"

namespace isg::formats {

namespace {

// Reads CDR: primitives aligned to their size, counted from the end of the encapsulation header.
class CdrReader {
 public:
  CdrReader(std::string_view bytes, const std::string& file, const std::string& where)
      : bytes_(bytes), file_(file), where_(where) {
    if (bytes_.size() < 4) fail("holds " + std::to_string(bytes_.size()) + " bytes, no CDR header");
    const auto kind = std::uint8_t(bytes_[1]);
    if (bytes_[0] != 0 || kind > 1) {
      fail("encapsulation " + std::to_string(std::uint8_t(bytes_[0])) + "," + std::to_string(kind) +
           " is not plain CDR (0,0 big-endian or 0,1 little-endian)");
    }
    little_ = kind == 1;
    at_ = 4;
  }

  std::uint32_t u32(const char* what) {
    align(4);
    need(4, what);
    std::uint8_t b[4];
    std::memcpy(b, bytes_.data() + at_, 4);
    at_ += 4;
    return little_ ? std::uint32_t(b[0]) | b[1] << 8 | b[2] << 16 | std::uint32_t(b[3]) << 24
                   : std::uint32_t(b[3]) | b[2] << 8 | b[1] << 16 | std::uint32_t(b[0]) << 24;
  }

  double time(const char* what) {
    const auto seconds = std::int32_t(u32(what));
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

  std::string bytes(std::size_t count, const char* what) {
    need(count, what);
    std::string out(bytes_.substr(at_, count));
    at_ += count;
    return out;
  }

  std::size_t remaining() const { return bytes_.size() - at_; }
  std::size_t position() const { return at_; }

  [[noreturn]] void fail(const std::string& reason) const {
    throw common::InputError(file_, "", where_ + ": " + reason);
  }

 private:
  void align(std::size_t n) { at_ = 4 + (at_ - 4 + n - 1) / n * n; }
  void need(std::size_t n, const char* what) const {
    if (at_ > bytes_.size() || bytes_.size() - at_ < n) {
      fail(std::string("ends inside ") + what + " (byte " + std::to_string(at_) + " of " +
           std::to_string(bytes_.size()) + ")");
    }
  }

  std::string_view bytes_;
  const std::string& file_;
  const std::string& where_;
  bool little_ = true;
  std::size_t at_ = 0;
};

}  // namespace

VelodyneScanMessage decodeVelodyneScanCdr(std::string_view bytes, const std::string& file,
                                          const std::string& where) {
  CdrReader cdr(bytes, file, where);
  VelodyneScanMessage scan;
  scan.stamp = cdr.time("header.stamp");
  scan.frame_id = cdr.string("header.frame_id");
  const std::uint32_t count = cdr.u32("packets");
  // Each packet takes at least its stamp and data: a count beyond that is damage, not memory.
  if (count > cdr.remaining() / (8 + kVlp16PacketBytes)) {
    cdr.fail(std::to_string(count) + " packets announced, the message holds at most " +
             std::to_string(cdr.remaining() / (8 + kVlp16PacketBytes)));
  }
  scan.packets.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    VelodynePacketRecord packet;
    packet.stamp = cdr.time("packets[].stamp");
    packet.data = cdr.bytes(kVlp16PacketBytes, "packets[].data");
    scan.packets.push_back(std::move(packet));
  }
  if (cdr.remaining() > 3) {  // CDR pads a message to 4 bytes, no more
    cdr.fail(std::to_string(cdr.remaining()) + " bytes after the last packet");
  }
  return scan;
}

}  // namespace isg::formats
