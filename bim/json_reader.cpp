#include "bim/json_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace isg::bim {

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
    throw InputError(source_->file, pointer_,
                     "missing required field \"" + std::string(key) + "\"");
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

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("expected a string, got " + describeJsonType(*value_));
  return value_->get<std::string>();
}

std::string JsonNode::nonEmptyString() const {
  std::string s = string();
  if (s.empty()) fail("must not be empty");
  return s;
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

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports a byte offset; people want a line and a column.
    std::size_t line = 1;
    std::size_t column = 1;
    const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: " prefix.
    if (auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(file, "",
                     "invalid JSON at line " + std::to_string(line) + ", column " +
                         std::to_string(column) + ": " + what);
  } catch (const nlohmann::json::exception& e) {
    // A number too large for a double (1e999): JSON has no infinity, and neither do we.
    std::string what = e.what();
    if (auto bracket = what.find("] "); bracket != std::string::npos)
      what = what.substr(bracket + 2);
    throw InputError(file, "", "invalid JSON: " + what + " (numbers must be finite)");
  }
}

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return parseJsonText(buffer.str(), path);
}

}  // namespace isg::bim
