// libFuzzer harness: bytes → the raw VLP-16 readers. The same bytes go to the pcap reader (and
// each datagram of the VLP-16's size to the packet decoder) and to the VelodyneScan CDR decoder
// (and each of its packets to the packet decoder).
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"
#include "formats/pcap_file.hpp"
#include "formats/velodyne_scan_cdr.hpp"
#include "formats/vlp16_packet.hpp"
#include "formats/vlp16_turns.hpp"

namespace {

void decode(const std::string& payload, std::vector<isg::formats::Vlp16Point>& points) {
  if (payload.size() != isg::formats::kVlp16PacketBytes) return;
  try {
    isg::formats::decodeVlp16Packet(
        std::span(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()), 0.0, {},
        "fuzz", "packet", points);
  } catch (const isg::common::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::vector<isg::formats::Vlp16Point> points;
  try {
    for (const auto& datagram : isg::formats::parsePcapUdp(bytes, "fuzz.pcap")) {
      decode(datagram.payload, points);
    }
  } catch (const isg::common::InputError&) {
  }
  try {
    const auto scan = isg::formats::decodeVelodyneScanCdr(bytes, "fuzz.db3", "message");
    for (const auto& packet : scan.packets) decode(packet.data, points);
  } catch (const isg::common::InputError&) {
  }
  isg::formats::cutIntoTurns(points, 0.0);
  return 0;
}
