#include "formats/file_bytes.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

std::unique_ptr<std::istream> openBinaryFile(const std::string& path) {
  common::checkRegularFile(path);
  auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
  if (!*file)
    throw common::InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
  return file;
}

bool readAt(std::istream& in, std::uint64_t offset, std::uint64_t size, std::string& out) {
  out.resize(size);
  in.clear();
  in.seekg(std::streamoff(offset));
  in.read(out.data(), std::streamsize(size));
  return in.gcount() == std::streamsize(size);
}

}  // namespace isg::formats
