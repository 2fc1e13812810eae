// libFuzzer harness: bytes → the dataset's PCD reader.
#include <cstdint>
#include <string_view>

#include "common/input_error.hpp"
#include "formats/pcd_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    isg::formats::parsePcd(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.pcd");
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
