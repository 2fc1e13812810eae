#pragma once

#include <cstdint>
#include <string_view>

// What MCAP's writer and reader share (https://mcap.dev/spec): the magic at both ends of a file
// and the opcodes of the records they write or read.
namespace isg::formats::mcap {

inline constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0b,
  kSummaryOffset = 0x0e,
  kDataEnd = 0x0f,
};

// Every record starts with its opcode and a uint64 length of its content.
inline constexpr std::uint64_t kRecordHead = 9;

}  // namespace isg::formats::mcap
