#pragma once

#include <cstdint>

namespace isg::formats::rosbag {

// The ROS 1 bag format 2.0 (docs/formats.md, "ROS bags"): what the writer and the reader share.
inline constexpr const char* kVersionLine = "#ROSBAG V2.0\n";

// A record's `op` header field.
enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07
};

}  // namespace isg::formats::rosbag
