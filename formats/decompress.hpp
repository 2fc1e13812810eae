#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace isg::formats {

// Decompresses `stored` — "bz2", "lz4" (the LZ4 frame format) or "zstd" — into exactly `size`
// bytes, growing the output as the data really yields it (a recording's claimed size is not
// trusted with an allocation). False, with `error` saying why, when the data is damaged, is cut
// short, or does not come to exactly `size` bytes. Used by the ROS 1 bag's chunks and MCAP's.
bool decompress(const std::string& compression, std::string_view stored, std::uint64_t size,
                std::string& out, std::string& error);

}  // namespace isg::formats
