// libFuzzer harness: bytes → the ROS 1 bag reader, every message read.
#include <cstdint>
#include <string>

#include "bim/input_error.hpp"
#include "sensors/rosbag_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    isg::sensors::RosbagReader reader(std::string(reinterpret_cast<const char*>(data), size),
                                      "fuzz.bag");
    std::size_t bytes = 0;
    reader.read({}, [&](const isg::sensors::BagMessageView& m) {
      bytes += m.data.size();
      return true;
    });
  } catch (const isg::bim::InputError&) {
  }
  return 0;
}
