#include "formats/velodyne_scan_cdr.hpp"

#include "common/input_error.hpp"
#include "formats/ros2_message_decode.hpp"

namespace isg::formats {

VelodyneScanMessage decodeVelodyneScanCdr(std::string_view bytes, const std::string& file,
                                          const std::string& where) {
  try {
    const ros1::VelodyneScan decoded = ros2::decodeVelodyneScan(bytes);
    const auto seconds = [](RosTime t) { return double(t.sec) + 1e-9 * t.nsec; };
    VelodyneScanMessage scan;
    scan.stamp = seconds(decoded.header.stamp);
    scan.frame_id = decoded.header.frame_id;
    scan.packets.reserve(decoded.packets.size());
    for (const auto& packet : decoded.packets) {
      scan.packets.push_back({seconds(packet.stamp), packet.data});
    }
    return scan;
  } catch (const ros1::MessageError& e) {
    throw common::InputError(file, "", where + ": " + e.what());
  }
}

}  // namespace isg::formats
