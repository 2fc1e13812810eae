#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace isg::formats {

// One raw packet of a velodyne_msgs/msg/VelodyneScan.
struct VelodynePacketRecord {
  double stamp = 0.0;  // s since the epoch (the driver's receive time)
  std::string data;    // the 1206-byte UDP payload
};

struct VelodyneScanMessage {
  double stamp = 0.0;
  std::string frame_id;
  std::vector<VelodynePacketRecord> packets;
};

// Decodes a CDR-serialised velodyne_msgs/msg/VelodyneScan (ROS 2: std_msgs/Header, then a
// sequence of VelodynePacket {builtin_interfaces/Time stamp, uint8[1206] data}), either byte
// order. A message that ends early or runs long is a common::InputError naming `file` and `where`.
VelodyneScanMessage decodeVelodyneScanCdr(std::string_view bytes, const std::string& file,
                                          const std::string& where);

}  // namespace isg::formats
