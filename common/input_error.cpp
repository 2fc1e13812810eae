#include "common/input_error.hpp"

namespace isg::common {

std::string formatLocated(const std::string& file, const std::string& pointer,
                          const std::string& text) {
  std::string out = file.empty() ? std::string("<input>") : file;
  out += ": ";
  if (!pointer.empty()) {
    out += pointer;
    out += ": ";
  }
  out += text;
  return out;
}

InputError::InputError(std::string file, std::string pointer, std::string reason)
    : std::runtime_error(formatLocated(file, pointer, reason)),
      file_(std::move(file)),
      pointer_(std::move(pointer)),
      reason_(std::move(reason)) {}

std::string InputWarning::str() const { return formatLocated(file, pointer, message); }

}  // namespace isg::common
