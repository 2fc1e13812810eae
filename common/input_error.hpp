#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace isg::common {

// A problem with a file a user wrote: which file, where in it (a JSON pointer such as
// "/levels/0/walls/3/thickness", empty for the whole file) and what is wrong. Every
// user-facing command turns this into one line on stderr and exit code 1.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string pointer, std::string reason);

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_;
  std::string pointer_;
  std::string reason_;
};

// Something odd but harmless (an unknown field, a clockwise outline): reported, never fatal.
struct InputWarning {
  std::string file;
  std::string pointer;
  std::string message;

  std::string str() const;
};

using Warnings = std::vector<InputWarning>;

// "file: /pointer: reason", or "file: reason" when the pointer is empty.
std::string formatLocated(const std::string& file, const std::string& pointer,
                          const std::string& text);

}  // namespace isg::common
