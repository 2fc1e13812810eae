#include "formats/pcap_file.hpp"

#include <cstdio>
#include <cstring>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

namespace {

constexpr std::uint32_t kMicrosecondMagic = 0xA1B2C3D4;
constexpr std::uint32_t kNanosecondMagic = 0xA1B23C4D;
constexpr std::uint32_t kLinkEthernet = 1;
constexpr std::uint32_t kLinkRawIp = 101;
constexpr std::uint32_t kLinkLinuxCooked = 113;

std::uint32_t swap32(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xFF00) | ((v << 8) & 0xFF0000) | (v << 24);
}

std::uint16_t bigEndian16(const std::uint8_t* at) { return std::uint16_t(at[0] << 8 | at[1]); }

class PcapParser {
 public:
  PcapParser(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  std::vector<UdpDatagram> parse(std::size_t* skipped) {
    if (bytes_.size() < 24)
      fail("", "holds " + std::to_string(bytes_.size()) + " bytes, fewer than a pcap header's 24");
    std::uint32_t magic = read32(0);
    if (magic == swap32(kMicrosecondMagic) || magic == swap32(kNanosecondMagic)) {
      swapped_ = true;
      magic = swap32(magic);
    }
    if (magic != kMicrosecondMagic && magic != kNanosecondMagic) {
      char text[16];
      std::snprintf(text, sizeof text, "0x%08X", unsigned(magic));
      fail("", std::string("not a pcap file (magic ") + text +
                   "; pcapng is not read: save as pcap, e.g. editcap -F pcap)");
    }
    const double tick = magic == kNanosecondMagic ? 1e-9 : 1e-6;
    const std::uint32_t link = read32(20) & 0x0FFFFFFF;  // the top bits may carry FCS flags
    if (link != kLinkEthernet && link != kLinkRawIp && link != kLinkLinuxCooked) {
      fail("", "link type " + std::to_string(link) +
                   " is none of Ethernet (1), raw IP (101), Linux cooked (113)");
    }
    std::vector<UdpDatagram> datagrams;
    std::size_t skipped_frames = 0;
    std::size_t at = 24;
    for (std::size_t record = 0; at < bytes_.size(); ++record) {
      const std::string where = "record " + std::to_string(record);
      if (bytes_.size() - at < 16) fail(where, "truncated record header");
      const std::uint32_t seconds = read32(at), fraction = read32(at + 4);
      const std::uint32_t captured = read32(at + 8);
      at += 16;
      if (captured > bytes_.size() - at) {
        fail(where, "announces " + std::to_string(captured) + " bytes, the file holds " +
                        std::to_string(bytes_.size() - at));
      }
      const auto* frame = reinterpret_cast<const std::uint8_t*>(bytes_.data() + at);
      at += captured;
      UdpDatagram datagram;
      datagram.stamp = seconds + fraction * tick;
      if (udpOf(frame, captured, link, where, datagram)) {
        datagrams.push_back(std::move(datagram));
      } else {
        ++skipped_frames;
      }
    }
    if (skipped) *skipped = skipped_frames;
    return datagrams;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& reason) const {
    throw common::InputError(file_, "", where.empty() ? reason : where + ": " + reason);
  }

  std::uint32_t read32(std::size_t at) const {
    std::uint32_t v;
    std::memcpy(&v, bytes_.data() + at, 4);
    return swapped_ ? swap32(v) : v;
  }

  // The frame's UDP payload over IPv4, or false for any other frame.
  bool udpOf(const std::uint8_t* frame, std::size_t size, std::uint32_t link,
             const std::string& where, UdpDatagram& out) const {
    std::size_t ip = 0;
    if (link == kLinkEthernet) {
      if (size < 14) return false;
      std::uint16_t type = bigEndian16(frame + 12);
      ip = 14;
      while (type == 0x8100 || type == 0x88A8) {  // 802.1Q / 802.1ad tags
        if (size < ip + 4) return false;
        type = bigEndian16(frame + ip + 2);
        ip += 4;
      }
      if (type != 0x0800) return false;
    } else if (link == kLinkLinuxCooked) {
      if (size < 16 || bigEndian16(frame + 14) != 0x0800) return false;
      ip = 16;
    }
    if (size < ip + 20 || frame[ip] >> 4 != 4) return false;
    const std::size_t header = (frame[ip] & 0x0F) * 4u;
    const bool fragment = (bigEndian16(frame + ip + 6) & 0x3FFF) != 0;
    if (frame[ip + 9] != 17 || header < 20 || fragment) return false;
    const std::size_t udp = ip + header;
    if (size < udp + 8) fail(where, "UDP header cut off by the capture");
    const std::size_t length = bigEndian16(frame + udp + 4);
    if (length < 8 || udp + length > size) {
      fail(where, "UDP length " + std::to_string(length) + " runs past the captured " +
                      std::to_string(size - udp) + " bytes");
    }
    out.source_port = bigEndian16(frame + udp);
    out.destination_port = bigEndian16(frame + udp + 2);
    out.payload.assign(reinterpret_cast<const char*>(frame + udp + 8), length - 8);
    return true;
  }

  std::string_view bytes_;
  const std::string& file_;
  bool swapped_ = false;
};

}  // namespace

std::vector<UdpDatagram> parsePcapUdp(std::string_view bytes, const std::string& file,
                                      std::size_t* skipped) {
  return PcapParser(bytes, file).parse(skipped);
}

std::vector<UdpDatagram> readPcapUdp(const std::string& path, std::size_t* skipped) {
  return parsePcapUdp(common::readCheckedFile(path, kMaxPcapBytes), path, skipped);
}

}  // namespace isg::formats
