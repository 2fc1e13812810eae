// libFuzzer harness: bytes → the TUM reader, and an accepted trajectory through association and
// APE against itself (what `isg eval` does with two files).
#include <cstdint>
#include <stdexcept>
#include <string>

#include "eval/ape.hpp"
#include "eval/tum.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const isg::eval::Trajectory trajectory = isg::eval::parseTum(text, "fuzz.tum");
    if (trajectory.empty()) return 0;
    isg::eval::ErrorOptions options;
    options.align = isg::eval::Alignment::kSE3;
    isg::eval::absolutePoseError(trajectory, trajectory, options);
  } catch (const isg::eval::TumError&) {
  } catch (const std::invalid_argument&) {
    // Too few or degenerate poses to align: the documented answer.
  }
  return 0;
}
