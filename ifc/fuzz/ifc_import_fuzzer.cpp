// libFuzzer harness: bytes → isg import (the STEP header check, IFC++'s reader and geometry, the
// import's fitting, the plan parser on what it wrote). An InputError is the expected answer to a
// bad file; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "ifc/ifc_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    isg::ifc::importIfcText("fuzz.ifc", std::move(text), {});
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
