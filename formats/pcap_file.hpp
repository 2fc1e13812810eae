#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace isg::formats {

// The largest capture file read whole (a VLP-16 sends ~0.9 MB/s: minutes of recording).
inline constexpr std::uintmax_t kMaxPcapBytes = 1u << 30;

// One UDP datagram of a capture.
struct UdpDatagram {
  double stamp = 0.0;  // s since the epoch, the capture's clock
  std::uint16_t source_port = 0;
  std::uint16_t destination_port = 0;
  std::string payload;
};

// The UDP datagrams over IPv4 of a classic pcap file (either byte order, µs or ns stamps; link
// types Ethernet with or without 802.1Q tags, Linux cooked capture, raw IPv4), in file order.
// Frames of other protocols are skipped and counted in `skipped` when given; IP fragments are
// skipped too (a VLP-16 datagram fits one frame). A damaged file — bad magic, a truncated record,
// a UDP length beyond its frame — is a common::InputError naming the file and the record.
std::vector<UdpDatagram> readPcapUdp(const std::string& path, std::size_t* skipped = nullptr);
std::vector<UdpDatagram> parsePcapUdp(std::string_view bytes, const std::string& file,
                                      std::size_t* skipped = nullptr);

}  // namespace isg::formats
