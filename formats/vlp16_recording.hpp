#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "formats/vlp16_packet.hpp"

namespace isg::formats {

// A real VLP-16's raw packets decoded: the returns in firing order and the shots per ring.
struct Vlp16Recording {
  std::vector<Vlp16Point> points;
  Vlp16ShotTally tally;
  std::size_t data_packets = 0;
  std::size_t position_packets = 0;  // the sensor's GPS/PPS packets (pcap only), not decoded
  Vlp16ReturnMode mode = Vlp16ReturnMode::kStrongest;
};

// Reads a pcap capture (.pcap: UDP datagrams of 1206 bytes are data packets, 512-byte ones
// position packets) or a ROS 2 bag (a folder or a .db3 file) of velodyne_msgs/msg/VelodyneScan on
// `topic` (found by its type when empty and only one topic has it). Each packet is stamped with
// its capture or driver receive time. Bad input is a common::InputError naming the file and the
// packet (pcap record or bag message and packet).
Vlp16Recording readVlp16Recording(const std::string& path, const Vlp16DecodeOptions& options,
                                  const std::string& topic = "");

}  // namespace isg::formats
