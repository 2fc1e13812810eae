#pragma once

#include <cstdint>
#include <istream>
#include <memory>
#include <string>

namespace isg::formats {

// What the container readers (ROS 1 bags, MCAP) share to read a file by offset.

// `path` opened for reading bytes once it is known to be a regular file (never a FIFO, which
// would wait for a writer); a common::InputError naming it otherwise.
std::unique_ptr<std::istream> openBinaryFile(const std::string& path);

// The `size` bytes at `offset` into `out`; false when the stream holds fewer. The caller bounds
// `size` by the file's size first: `out` is resized to it.
bool readAt(std::istream& in, std::uint64_t offset, std::uint64_t size, std::string& out);

}  // namespace isg::formats
