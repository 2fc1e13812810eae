#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"

namespace isg::common {

// Where a JSON document came from, and where its warnings go.
struct JsonSource {
  std::string file;
  Warnings* warnings = nullptr;
};

// A JSON value together with its JSON pointer and file, so that every accessor can fail with an
// InputError that says exactly where the problem is. Accessors check types strictly: a number
// written as a string is an error, never silently converted.
class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string pointer, const JsonSource& source);

  const std::string& pointer() const { return pointer_; }
  const nlohmann::json& raw() const { return *value_; }
  const JsonSource& source() const { return *source_; }

  // Object access. `field` fails when the key is missing; `optionalField` returns nullopt.
  JsonNode field(std::string_view key) const;
  std::optional<JsonNode> optionalField(std::string_view key) const;
  bool has(std::string_view key) const;
  // Requires an object and warns about every key not in `known` (unknown fields are ignored).
  void expectObject(std::initializer_list<std::string_view> known) const;

  // Array access.
  std::vector<JsonNode> elements() const;
  std::vector<JsonNode> elements(std::size_t min_size) const;
  // At least `min_size` and at most `max_size` elements; `what` names them in the message
  // ("walls"), which points at the stated limit.
  std::vector<JsonNode> elements(std::size_t min_size, std::size_t max_size,
                                 const std::string& what) const;

  // Scalars.
  double number() const;          // finite
  double positiveNumber() const;  // finite and > 0
  double nonNegativeNumber() const;
  double numberInRange(double lo, double hi, bool hi_open = false) const;  // [lo, hi] or [lo, hi)
  std::uint64_t unsignedInteger() const;
  std::int64_t integer() const;  // any integer a 64-bit signed one holds
  std::string string() const;
  std::string nonEmptyString() const;
  // An id: non-empty, at most limits::kMaxIdBytes bytes, no control characters (they would
  // break the XML of a world and every message that quotes the id).
  std::string identifier() const;
  // Free text (a name, a file name): at most limits::kMaxTextBytes bytes, no control characters.
  std::string text() const;
  bool boolean() const;

  // [x, y] and [x, y, z] arrays of finite numbers.
  Eigen::Vector2d point2() const;
  Eigen::Vector3d point3() const;
  std::vector<double> numbers(std::size_t exact_size) const;

  bool isString() const { return value_->is_string(); }
  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }

  [[noreturn]] void fail(const std::string& reason) const;
  void warn(const std::string& message) const;

 private:
  // `s` unless it is longer than `max_bytes` or holds a control character (`control_rule` says
  // why not); `what` names it in the message.
  std::string checkedText(std::string s, std::size_t max_bytes, const char* what,
                          const char* control_rule) const;

  const nlohmann::json* value_;
  std::string pointer_;
  const JsonSource* source_;
};

// Appends a reference token to a JSON pointer, escaping '~' and '/' as RFC 6901 requires.
std::string appendPointer(const std::string& pointer, std::string_view token);
std::string appendPointer(const std::string& pointer, std::size_t index);

// "R1" with its quotes, and a number as people write it (0.15, not 0.150000), for messages.
std::string inQuotes(const std::string& text);
std::string formatNumber(double value);

// "an object", "a string", ... for messages about a value of the wrong type.
std::string describeJsonType(const nlohmann::json& value);

// Checks the "format" and "version" fields every document of ours starts with.
void checkFormatAndVersion(const JsonNode& root, const std::string& format, int version);

// Reads and parses a JSON file; a missing file or a syntax error is an InputError naming the
// file (and the line and column of a syntax error).
nlohmann::json readJsonFile(const std::string& path);
// Fails unless `path` names a regular file, before anything opens it: opening a FIFO waits for a
// writer that may never come, and a device (/dev/zero) never ends. Readers that open a file
// themselves (the bag and MCAP readers, SQLite) call it first.
void checkRegularFile(const std::string& path);
// Fails unless `path` is a regular file of at most `max_bytes` bytes: a device such as /dev/zero
// or a FIFO is never read, and no file is read past a stated limit.
void checkReadableFile(const std::string& path, std::uintmax_t max_bytes);
// The whole of a file checked by checkReadableFile; problems are InputErrors naming it.
std::string readCheckedFile(const std::string& path, std::uintmax_t max_bytes);
nlohmann::json parseJsonText(const std::string& text, const std::string& file);

}  // namespace isg::common
