#include "formats/vlp16_recording.hpp"

#include <filesystem>
#include <span>

#include "common/input_error.hpp"
#include "formats/pcap_file.hpp"
#include "formats/ros2_bag.hpp"
#include "formats/velodyne_scan_cdr.hpp"

namespace isg::formats {

namespace {

constexpr std::size_t kPositionPacketBytes = 512;
constexpr const char* kScanType = "velodyne_msgs/msg/VelodyneScan";

std::span<const std::uint8_t> byteSpan(const std::string& data) {
  return {reinterpret_cast<const std::uint8_t*>(data.data()), data.size()};
}

void decodeInto(Vlp16Recording& recording, const std::string& data, double stamp,
                const Vlp16DecodeOptions& options, const std::string& file,
                const std::string& where) {
  // A packet of another mode throws with the recording half-decoded: the caller never sees it.
  const Vlp16PacketHeader header = decodeVlp16Packet(byteSpan(data), stamp, options, file, where,
                                                     recording.points, &recording.tally);
  if (recording.data_packets > 0 && header.mode != recording.mode) {
    throw common::InputError(file, "", where + ": the return mode changes within the recording");
  }
  recording.mode = header.mode;
  ++recording.data_packets;
}

Vlp16Recording fromPcap(const std::string& path, const Vlp16DecodeOptions& options) {
  Vlp16Recording recording;
  const auto datagrams = readPcapUdp(path);
  for (std::size_t i = 0; i < datagrams.size(); ++i) {
    const auto& datagram = datagrams[i];
    if (datagram.payload.size() == kVlp16PacketBytes) {
      decodeInto(recording, datagram.payload, datagram.stamp, options, path,
                 "UDP datagram " + std::to_string(i));
    } else if (datagram.payload.size() == kPositionPacketBytes) {
      ++recording.position_packets;
    }
  }
  if (recording.data_packets == 0) {
    throw common::InputError(path, "", "no VLP-16 data packets (UDP payloads of 1206 bytes)");
  }
  return recording;
}

std::string scanTopic(const Ros2Bag& bag, const std::string& path, const std::string& topic) {
  if (!topic.empty()) return topic;
  std::vector<std::string> found;
  for (const auto& t : bag.topics()) {
    if (t.type == kScanType) found.push_back(t.name);
  }
  if (found.size() == 1) return found.front();
  std::string names;
  for (const auto& t : bag.topics())
    names += (names.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  throw common::InputError(
      path, "",
      found.empty() ? std::string("no topic of type ") + kScanType + " (the bag has: " + names + ")"
                    : "several topics of type " + std::string(kScanType) +
                          ": name one (the bag has: " + names + ")");
}

Vlp16Recording fromBag(const std::string& path, const Vlp16DecodeOptions& options,
                       const std::string& topic) {
  const Ros2Bag bag(path);
  const std::string name = scanTopic(bag, path, topic);
  Vlp16Recording recording;
  const auto messages = bag.messages(name);
  for (std::size_t m = 0; m < messages.size(); ++m) {
    const std::string where = name + " message " + std::to_string(m);
    const VelodyneScanMessage scan = decodeVelodyneScanCdr(messages[m].data, path, where);
    for (std::size_t p = 0; p < scan.packets.size(); ++p) {
      decodeInto(recording, scan.packets[p].data, scan.packets[p].stamp, options, path,
                 where + " packet " + std::to_string(p));
    }
  }
  if (recording.data_packets == 0) throw common::InputError(path, "", name + " holds no packets");
  return recording;
}

}  // namespace

Vlp16Recording readVlp16Recording(const std::string& path, const Vlp16DecodeOptions& options,
                                  const std::string& topic) {
  const std::filesystem::path file(path);
  if (file.extension() == ".pcap") return fromPcap(path, options);
  return fromBag(path, options, topic);
}

}  // namespace isg::formats
