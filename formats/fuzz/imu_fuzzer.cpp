// libFuzzer harness: bytes → the dataset's imu.csv reader.
#include <cstdint>
#include <string_view>

#include "common/input_error.hpp"
#include "formats/imu_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    isg::formats::parseImuText(std::string_view(reinterpret_cast<const char*>(data), size),
                               "fuzz.csv");
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
