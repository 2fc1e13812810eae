#include "formats/map_yaml.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "common/decimal_number.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// A value with its quotes taken off (YAML's plain, single- and double-quoted scalars, without
// escapes).
std::string unquote(const std::string& value) {
  if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') &&
      value.back() == value.front()) {
    return value.substr(1, value.size() - 2);
  }
  return value;
}

// The value with a trailing comment taken off (a # after a space, outside quotes).
std::string withoutComment(const std::string& value) {
  char quote = 0;
  for (std::size_t k = 0; k < value.size(); ++k) {
    const char c = value[k];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && (k == 0 || value[k - 1] == ' ' || value[k - 1] == '\t')) {
      return trim(value.substr(0, k));
    }
  }
  return value;
}

struct Entry {
  std::string value;
  int line = 0;
};

// The file's top-level `key: value` lines, each once, with the lines they stand on for messages.
class MapYamlEntries {
 public:
  MapYamlEntries(const std::string& text, const std::string& path) : path_(path) {
    int line_number = 0;
    std::size_t at = 0;
    while (at <= text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      const std::string line = text.substr(at, end - at);
      at = end + 1;
      ++line_number;
      const std::string content = trim(line);
      if (content.empty() || content[0] == '#' || content == "---" || content == "...") continue;
      if (line.find_first_not_of(" \t") != 0) continue;  // nested under another key
      const auto colon = content.find(':');
      if (colon == std::string::npos) {
        throw common::InputError(path, "",
                                 "line " + std::to_string(line_number) +
                                     ": expected `key: value`, found \"" + content + "\"");
      }
      const std::string key = trim(content.substr(0, colon));
      const std::string value = withoutComment(trim(content.substr(colon + 1)));
      if (entries_.count(key)) {
        throw common::InputError(path, "/" + key,
                                 "line " + std::to_string(line_number) +
                                     ": given twice (also on line " +
                                     std::to_string(entries_[key].line) + ")");
      }
      entries_[key] = {value, line_number};
    }
  }

  const Entry& required(const std::string& key) const {
    const auto found = entries_.find(key);
    if (found == entries_.end() || found->second.value.empty()) {
      throw common::InputError(path_, "/" + key,
                               "missing: a map's YAML names its image, resolution, origin, "
                               "negate, occupied_thresh and free_thresh (as map_server requires)");
    }
    return found->second;
  }
  const Entry* optional(const std::string& key) const {
    const auto found = entries_.find(key);
    return found == entries_.end() ? nullptr : &found->second;
  }

  double number(const std::string& key, const std::string& text_value, int line) const {
    // Decimal only: an empty element ("origin: [, , ]") is no zero, and "0x10" no sixteen.
    const std::optional<double> number = common::parseDecimal(text_value);
    const double value = number.value_or(0.0);
    if (!number) {
      throw common::InputError(
          path_, "/" + key,
          "line " + std::to_string(line) + ": \"" + text_value + "\" is not a finite number");
    }
    return value;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::map<std::string, Entry> entries_;
};

// origin: [x, y, yaw], x and y within ±10 000 m.
void readOrigin(const MapYamlEntries& entries, MapYaml& map) {
  const std::string& path = entries.path();
  const Entry& origin = entries.required("origin");
  std::string list = origin.value;
  if (list.size() < 2 || list.front() != '[' || list.back() != ']') {
    throw common::InputError(
        path, "/origin",
        "line " + std::to_string(origin.line) + ": expected [x, y, yaw], found \"" + list + "\"");
  }
  list = list.substr(1, list.size() - 2);
  std::vector<double> values;
  std::size_t from = 0;
  while (from <= list.size()) {
    const std::size_t comma = std::min(list.find(',', from), list.size());
    values.push_back(entries.number("origin/" + std::to_string(values.size()),
                                    trim(list.substr(from, comma - from)), origin.line));
    from = comma + 1;
  }
  if (values.size() != 3) {
    throw common::InputError(path, "/origin",
                             "line " + std::to_string(origin.line) +
                                 ": the origin has 3 elements, [x, y, yaw], not " +
                                 std::to_string(values.size()));
  }
  for (int k = 0; k < 2; ++k) {
    if (std::abs(values[k]) > 10'000.0) {
      throw common::InputError(
          path, "/origin/" + std::to_string(k),
          "line " + std::to_string(origin.line) + ": beyond ±10 000 m of the map frame's origin");
    }
  }
  map.origin_x = values[0], map.origin_y = values[1], map.origin_yaw = values[2];
}

// negate, occupied_thresh, free_thresh and the optional mode: how pixels are classed.
void readOccupancyRule(const MapYamlEntries& entries, OccupancyRule& rule) {
  const std::string& path = entries.path();
  const Entry& negate = entries.required("negate");
  const std::string v = unquote(negate.value);
  if (v == "0" || v == "false" || v == "False" || v == "FALSE") {
    rule.negate = false;
  } else if (v == "1" || v == "true" || v == "True" || v == "TRUE") {
    rule.negate = true;
  } else {
    throw common::InputError(path, "/negate",
                             "line " + std::to_string(negate.line) +
                                 ": expected 0, 1, true or "
                                 "false, found \"" +
                                 v + "\"");
  }
  for (const char* key : {"occupied_thresh", "free_thresh"}) {
    const Entry& entry = entries.required(key);
    const double value = entries.number(key, entry.value, entry.line);
    if (value < 0.0 || value > 1.0) {
      throw common::InputError(path, std::string("/") + key,
                               "line " + std::to_string(entry.line) + ": must lie in [0, 1]");
    }
    (std::string(key) == "occupied_thresh" ? rule.occupied_thresh : rule.free_thresh) = value;
  }
  if (rule.free_thresh > rule.occupied_thresh) {
    throw common::InputError(path, "/free_thresh",
                             "line " + std::to_string(entries.required("free_thresh").line) +
                                 ": above occupied_thresh: no pixel could be both");
  }
  if (const Entry* mode = entries.optional("mode")) {
    const std::string m = unquote(mode->value);
    if (m == "trinary") {
      rule.mode = OccupancyRule::Mode::kTrinary;
    } else if (m == "scale") {
      rule.mode = OccupancyRule::Mode::kScale;
    } else if (m == "raw") {
      rule.mode = OccupancyRule::Mode::kRaw;
    } else {
      throw common::InputError(path, "/mode",
                               "line " + std::to_string(mode->line) +
                                   ": expected trinary, scale or raw, found \"" + m + "\"");
    }
  }
}

}  // namespace

MapYaml parseMapYaml(const std::string& text_in, const std::string& path) {
  // A UTF-8 byte order mark (some editors write one) is no part of the first key.
  const std::string text = text_in.rfind("\xEF\xBB\xBF", 0) == 0 ? text_in.substr(3) : text_in;
  const MapYamlEntries entries(text, path);
  MapYaml map;
  const Entry& image = entries.required("image");
  if (unquote(image.value).empty()) {
    throw common::InputError(path, "/image",
                             "line " + std::to_string(image.line) +
                                 ": the image is empty: name the map's PNG or PGM file");
  }
  const std::filesystem::path image_path(unquote(image.value));
  map.image = image_path.is_absolute()
                  ? image_path.string()
                  : (std::filesystem::path(path).parent_path() / image_path).string();
  const Entry& resolution = entries.required("resolution");
  map.resolution = entries.number("resolution", resolution.value, resolution.line);
  if (!(map.resolution > 0.0) || map.resolution > 10.0) {
    throw common::InputError(path, "/resolution",
                             "line " + std::to_string(resolution.line) +
                                 ": must be above 0 and at most 10 (metres a pixel)");
  }
  readOrigin(entries, map);
  readOccupancyRule(entries, map.rule);
  return map;
}

MapYaml readMapYaml(const std::string& path) {
  return parseMapYaml(common::readCheckedFile(path, 1 << 20), path);
}

}  // namespace isg::formats
