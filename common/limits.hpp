#pragma once

#include <cstddef>
#include <cstdint>

// The limits every JSON document of ours is held to, whatever it describes (docs/formats.md,
// "Limits"); a plan's own limits (coordinates, counts of walls and rooms) are bim/limits.hpp's.
namespace isg::common::limits {

// Plan, scenario, suite and metadata JSON files: regular files of at most this many bytes.
inline constexpr std::uintmax_t kMaxJsonFileBytes = 32u << 20;

// Ids ("W1") and free text (names, file names inside a document): bytes, no control characters.
inline constexpr std::size_t kMaxIdBytes = 128;
inline constexpr std::size_t kMaxTextBytes = 1024;

}  // namespace isg::common::limits
