// libFuzzer harness: bytes → the TUM reader, and an accepted trajectory through association and
// APE against itself (what `isg eval` does with two files).
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/tum.hpp"
#include "eval/ape.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const isg::common::Trajectory trajectory = isg::common::parseTum(text, "fuzz.tum");
    if (trajectory.empty()) return 0;
    isg::eval::ErrorOptions options;
    options.align = isg::eval::Alignment::kSE3;
    isg::eval::absolutePoseError(trajectory, trajectory, options);
  } catch (const isg::common::TumError&) {
  } catch (const std::invalid_argument&) {
    // Too few or degenerate poses to align: the documented answer.
  }
  return 0;
}
