#include "common/json_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/limits.hpp"

namespace isg::common {

std::string inQuotes(const std::string& text) { return "\"" + text + "\""; }

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string appendPointer(const std::string& pointer, std::string_view token) {
  std::string out = pointer;
  out += '/';
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string appendPointer(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

std::string describeJsonType(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

JsonNode::JsonNode(const nlohmann::json& value, std::string pointer, const JsonSource& source)
    : value_(&value), pointer_(std::move(pointer)), source_(&source) {}

void JsonNode::fail(const std::string& reason) const {
  throw InputError(source_->file, pointer_, reason);
}

void JsonNode::warn(const std::string& message) const {
  if (source_->warnings != nullptr) {
    source_->warnings->push_back({source_->file, pointer_, message});
  }
}

bool JsonNode::has(std::string_view key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::field(std::string_view key) const {
  if (!value_->is_object()) fail("expected an object, got " + describeJsonType(*value_));
  auto it = value_->find(key);
  if (it == value_->end()) {
    throw InputError(source_->file, appendPointer(pointer_, key), "missing required field");
  }
  return JsonNode(*it, appendPointer(pointer_, key), *source_);
}

std::optional<JsonNode> JsonNode::optionalField(std::string_view key) const {
  if (!value_->is_object()) fail("expected an object, got " + describeJsonType(*value_));
  auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonNode(*it, appendPointer(pointer_, key), *source_);
}

void JsonNode::expectObject(std::initializer_list<std::string_view> known) const {
  if (!value_->is_object()) fail("expected an object, got " + describeJsonType(*value_));
  for (const auto& [key, unused] : value_->items()) {
    bool is_known = false;
    for (std::string_view k : known) is_known = is_known || k == key;
    if (!is_known) {
      JsonNode(unused, appendPointer(pointer_, key), *source_)
          .warn("unknown field \"" + key + "\" (ignored)");
    }
  }
}

std::vector<JsonNode> JsonNode::elements() const {
  if (!value_->is_array()) fail("expected an array, got " + describeJsonType(*value_));
  std::vector<JsonNode> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) {
    out.emplace_back((*value_)[i], appendPointer(pointer_, i), *source_);
  }
  return out;
}

std::vector<JsonNode> JsonNode::elements(std::size_t min_size) const {
  auto out = elements();
  if (out.size() < min_size) {
    fail("expected at least " + std::to_string(min_size) + " element" + (min_size == 1 ? "" : "s") +
         ", got " + std::to_string(out.size()));
  }
  return out;
}

std::vector<JsonNode> JsonNode::elements(std::size_t min_size, std::size_t max_size,
                                         const std::string& what) const {
  if (!value_->is_array()) fail("expected an array, got " + describeJsonType(*value_));
  if (value_->size() > max_size) {
    fail(std::to_string(value_->size()) + " " + what + "; at most " + std::to_string(max_size) +
         " are supported (docs/formats.md, Limits)");
  }
  return elements(min_size);
}

double JsonNode::numberInRange(double lo, double hi, bool hi_open) const {
  const double v = number();
  if (v < lo || v > hi || (hi_open && v >= hi)) {
    fail("must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + (hi_open ? ")" : "]") +
         ", got " + formatNumber(v));
  }
  return v;
}

double JsonNode::number() const {
  if (!value_->is_number()) fail("expected a number, got " + describeJsonType(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number, got " + formatNumber(v));
  return v;
}

double JsonNode::positiveNumber() const {
  const double v = number();
  if (!(v > 0.0)) fail("must be > 0, got " + formatNumber(v));
  return v;
}

double JsonNode::nonNegativeNumber() const {
  const double v = number();
  if (v < 0.0) fail("must be >= 0, got " + formatNumber(v));
  return v;
}

std::uint64_t JsonNode::unsignedInteger() const {
  if (value_->is_number_unsigned()) return value_->get<std::uint64_t>();
  if (value_->is_number_integer()) {
    fail("must be >= 0, got " + std::to_string(value_->get<std::int64_t>()));
  }
  fail("expected a non-negative integer, got " + describeJsonType(*value_));
}

std::int64_t JsonNode::integer() const {
  if (value_->is_number_unsigned()) {
    const std::uint64_t v = value_->get<std::uint64_t>();
    if (v > std::uint64_t(std::numeric_limits<std::int64_t>::max())) {
      fail("too large: " + std::to_string(v));
    }
    return std::int64_t(v);
  }
  if (value_->is_number_integer()) return value_->get<std::int64_t>();
  fail("expected an integer, got " + describeJsonType(*value_));
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("expected a string, got " + describeJsonType(*value_));
  return value_->get<std::string>();
}

std::string JsonNode::nonEmptyString() const {
  std::string s = string();
  if (s.empty()) fail("must not be empty");
  return s;
}

namespace {

// The first control character (U+0000-U+001F, U+007F) of a UTF-8 string, or npos.
std::size_t findControlCharacter(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte < 0x20 || byte == 0x7f) return i;
  }
  return std::string::npos;
}

std::string describeByte(char c) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "U+%04X",
                static_cast<unsigned>(static_cast<unsigned char>(c)));
  return buffer;
}

}  // namespace

std::string JsonNode::checkedText(std::string s, std::size_t max_bytes, const char* what,
                                  const char* control_rule) const {
  if (s.size() > max_bytes) {
    fail(std::string(what) + " of " + std::to_string(s.size()) + " bytes; at most " +
         std::to_string(max_bytes) + " are supported");
  }
  if (auto at = findControlCharacter(s); at != std::string::npos) {
    fail("control character " + describeByte(s[at]) + " at byte " + std::to_string(at) + " (" +
         control_rule + ")");
  }
  return s;
}

std::string JsonNode::text() const {
  return checkedText(string(), limits::kMaxTextBytes, "text", "control characters are not allowed");
}

std::string JsonNode::identifier() const {
  return checkedText(nonEmptyString(), limits::kMaxIdBytes, "id", "not allowed in ids");
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("expected a boolean, got " + describeJsonType(*value_));
  return value_->get<bool>();
}

std::vector<double> JsonNode::numbers(std::size_t exact_size) const {
  auto items = elements();
  if (items.size() != exact_size) {
    fail("expected an array of " + std::to_string(exact_size) + " numbers, got " +
         std::to_string(items.size()) + " element" + (items.size() == 1 ? "" : "s"));
  }
  std::vector<double> out;
  out.reserve(items.size());
  for (const auto& item : items) out.push_back(item.number());
  return out;
}

Eigen::Vector2d JsonNode::point2() const {
  auto v = numbers(2);
  return {v[0], v[1]};
}

Eigen::Vector3d JsonNode::point3() const {
  auto v = numbers(3);
  return {v[0], v[1], v[2]};
}

void checkFormatAndVersion(const JsonNode& root, const std::string& format, int version) {
  const JsonNode format_node = root.field("format");
  const std::string got = format_node.string();
  if (got != format) {
    format_node.fail("unknown format \"" + got + "\" (expected \"" + format + "\")");
  }
  const JsonNode version_node = root.field("version");
  if (!version_node.raw().is_number_integer()) {
    version_node.fail("expected an integer version, got " + describeJsonType(version_node.raw()));
  }
  const auto got_version = version_node.raw().get<std::int64_t>();
  if (got_version != version) {
    version_node.fail("unsupported version " + std::to_string(got_version) +
                      " (this build reads version " + std::to_string(version) + ")");
  }
}

namespace {

// Builds the document like nlohmann's own DOM parser and keeps the JSON pointer of the value
// being read, so that an error inside a value (a number too large for a double) names it.
class PointerTrackingSax : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit PointerTrackingSax(nlohmann::json& result) : dom_(result, false) {}

  bool null() override { return scalar(dom_.null()); }
  bool boolean(bool v) override { return scalar(dom_.boolean(v)); }
  bool number_integer(number_integer_t v) override { return scalar(dom_.number_integer(v)); }
  bool number_unsigned(number_unsigned_t v) override { return scalar(dom_.number_unsigned(v)); }
  bool number_float(number_float_t v, const string_t& text) override {
    return scalar(dom_.number_float(v, text));
  }
  bool string(string_t& v) override { return scalar(dom_.string(v)); }
  bool binary(binary_t& v) override { return scalar(dom_.binary(v)); }
  bool start_object(std::size_t n) override {
    frames_.push_back({false, 0, ""});
    return dom_.start_object(n);
  }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() override {
    frames_.pop_back();
    return scalar(dom_.end_object());
  }
  bool start_array(std::size_t n) override {
    frames_.push_back({true, 0, ""});
    return dom_.start_array(n);
  }
  bool end_array() override {
    frames_.pop_back();
    return scalar(dom_.end_array());
  }
  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& error) override {
    error_position_ = position;
    error_ = error.what();
    (void)token;
    return false;
  }

  // Where the parser was when it stopped: the value it was reading.
  std::string pointer() const {
    std::string out;
    for (const auto& f : frames_) {
      out = f.is_array ? appendPointer(out, f.index) : appendPointer(out, f.key);
    }
    return out;
  }
  const std::string& error() const { return error_; }
  std::size_t errorPosition() const { return error_position_; }

 private:
  struct Frame {
    bool is_array;
    std::size_t index;
    std::string key;
  };
  // A finished value moves its array on to the next index.
  bool scalar(bool ok) {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
    return ok;
  }

  nlohmann::detail::json_sax_dom_parser<nlohmann::json> dom_;
  std::vector<Frame> frames_;
  std::string error_;
  std::size_t error_position_ = 0;
};

}  // namespace

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
  nlohmann::json document;
  PointerTrackingSax sax(document);
  if (nlohmann::json::sax_parse(text, &sax, nlohmann::json::input_format_t::json, false)) {
    return document;
  }
  std::string what = sax.error();
  // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: " prefix.
  if (auto colon = what.find(": "); colon != std::string::npos) {
    what = what.substr(colon + 2);
  } else if (auto bracket = what.find("] "); bracket != std::string::npos) {
    what = what.substr(bracket + 2);
  }
  // nlohmann reports a byte offset; people want a line and a column.
  std::size_t line = 1;
  std::size_t column = 1;
  const std::size_t position = sax.errorPosition();
  const std::size_t end = std::min<std::size_t>(position == 0 ? 0 : position - 1, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  const std::string where =
      "at line " + std::to_string(line) + ", column " + std::to_string(column);
  if (sax.error().find("out_of_range") != std::string::npos) {
    // A number too large for a double (1e999): JSON has no infinity, and neither do we.
    throw InputError(file, sax.pointer(), what + " " + where + " (numbers must be finite)");
  }
  throw InputError(file, "", "invalid JSON " + where + ": " + what);
}

void checkRegularFile(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    throw InputError(
        path, "",
        "cannot open file: " + (error ? error.message() : std::string(std::strerror(ENOENT))));
  }
  // Devices and pipes (/dev/zero, a FIFO) could be read, or waited on, forever: only regular
  // files are read.
  if (std::filesystem::is_directory(status))
    throw InputError(path, "", "is a directory, not a file");
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(path, "",
                     std::filesystem::is_fifo(status)
                         ? "not a regular file but a FIFO (a named pipe): only files are read"
                         : "not a regular file");
  }
}

void checkReadableFile(const std::string& path, std::uintmax_t max_bytes) {
  checkRegularFile(path);
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  if (error) throw InputError(path, "", "cannot read file: " + error.message());
  if (bytes > max_bytes) {
    throw InputError(path, "",
                     "file is " + std::to_string(bytes) + " bytes; at most " +
                         std::to_string(max_bytes) + " are read (docs/formats.md, Limits)");
  }
}

std::string readCheckedFile(const std::string& path, std::uintmax_t max_bytes) {
  checkReadableFile(path, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return buffer.str();
}

nlohmann::json readJsonFile(const std::string& path) {
  return parseJsonText(readCheckedFile(path, limits::kMaxJsonFileBytes), path);
}

}  // namespace isg::common
