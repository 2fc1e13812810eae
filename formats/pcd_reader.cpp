#include "formats/pcd_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <lzf.h>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

namespace {

// Quoted bytes of a damaged file, with anything unprintable shown as '?', at most 60 of them.
std::string printable(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 60)) {
    const auto byte = static_cast<unsigned char>(c);
    out += byte < 0x20 || byte >= 0x7f ? '?' : c;
  }
  return "\"" + out + "\"";
}

struct PcdField {
  std::string name;
  int size = 4;
  char type = 'F';
  int count = 1;
  std::size_t offset = 0;  // bytes from the start of a point (binary data)
  std::size_t column = 0;  // first token of the point's line (ascii data)
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0;
  std::size_t height = 1;
  std::optional<std::size_t> points;
  std::string data;
  std::size_t point_bytes = 0;
  std::size_t tokens_per_point = 0;
};

class PcdParser {
 public:
  PcdParser(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  std::vector<sensors::ScanPoint> parse() {
    const PcdHeader header = readHeader();
    const PcdField* x = find(header, "x");
    const PcdField* y = find(header, "y");
    const PcdField* z = find(header, "z");
    const PcdField* time = find(header, "time");
    if (!x || !y || !z || !time) failHeader("needs the fields x, y, z and time");
    const PcdField* intensity = find(header, "intensity");
    const PcdField* ring = find(header, "ring");
    std::vector<sensors::ScanPoint> points;
    points.reserve(std::min<std::size_t>(header.width * header.height, 1u << 20));
    forEachPoint(header, [&](auto value) {
      const double vx = value(*x), vy = value(*y), vz = value(*z), vt = value(*time);
      if (!std::isfinite(vx) || !std::isfinite(vy) || !std::isfinite(vz) || !std::isfinite(vt)) {
        return;
      }
      const double vi = intensity ? value(*intensity) : 0.0;
      const double vr = ring ? value(*ring) : 0.0;
      const double ring_index = std::isfinite(vr) ? std::clamp(vr, 0.0, 65535.0) : 0.0;
      points.push_back({float(vx), float(vy), float(vz), std::isfinite(vi) ? float(vi) : 0.0f,
                        std::uint16_t(ring_index), float(vt)});
    });
    return points;
  }

  PcdColumns columns() {
    const PcdHeader header = readHeader();
    PcdColumns table;
    for (const auto& f : header.fields) {
      if (f.count != 1)
        failHeader("field " + f.name + " has COUNT " + std::to_string(f.count) +
                   ": only COUNT 1 fields are read as columns");
      table.names.push_back(f.name);
    }
    table.values.resize(header.fields.size());
    for (auto& column : table.values) {
      column.reserve(std::min<std::size_t>(header.width * header.height, 1u << 20));
    }
    forEachPoint(header, [&](auto value) {
      for (std::size_t k = 0; k < header.fields.size(); ++k) {
        table.values[k].push_back(value(header.fields[k]));
      }
    });
    return table;
  }

 private:
  // Calls visit(value) for each point, where value(field) is that field's number in the point,
  // whatever the DATA kind.
  template <class Visit>
  void forEachPoint(const PcdHeader& header, Visit&& visit) {
    const std::size_t n = header.width * header.height;
    if (header.data == "binary") {
      const std::string_view data = bytes_.substr(position_);
      if (data.size() / header.point_bytes < n) {
        fail("data: " + std::to_string(n) + " points need " +
             std::to_string(n * header.point_bytes) + " bytes, the file holds " +
             std::to_string(data.size()));
      }
      for (std::size_t i = 0; i < n; ++i) {
        const char* point = data.data() + i * header.point_bytes;
        visit([point](const PcdField& f) { return binaryValue(point + f.offset, f); });
      }
    } else if (header.data == "binary_compressed") {
      // Field after field: field f of point i sits at n · offset(f) + i · bytes(f).
      const std::string columns = decompress(header, n);
      for (std::size_t i = 0; i < n; ++i) {
        visit([&columns, n, i](const PcdField& f) {
          return binaryValue(columns.data() + n * f.offset + i * f.size * f.count, f);
        });
      }
    } else {
      std::vector<double> values(header.tokens_per_point);
      for (std::size_t i = 0; i < n; ++i) {
        const std::string_view line = nextLine();
        if (line.data() == nullptr) {
          fail("data: " + std::to_string(n) + " points announced, the file ends after " +
               std::to_string(i));
        }
        const auto tokens = split(line);
        if (tokens.size() != header.tokens_per_point) {
          failLine("point " + std::to_string(i) + " has " + std::to_string(tokens.size()) +
                   " values, expected " + std::to_string(header.tokens_per_point));
        }
        for (std::size_t k = 0; k < tokens.size(); ++k) values[k] = asciiNumber(tokens[k]);
        visit([&values](const PcdField& f) { return values[f.column]; });
      }
    }
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw common::InputError(file_, "", reason);
  }
  [[noreturn]] void failLine(const std::string& reason) const {
    fail("line " + std::to_string(line_) + ": " + reason);
  }
  [[noreturn]] void failHeader(const std::string& reason) const { fail("header: " + reason); }

  // The next line (without its end), or a null view at the end of the file.
  std::string_view nextLine() {
    if (position_ >= bytes_.size()) return {};
    const std::size_t end = bytes_.find('\n', position_);
    const std::size_t stop = end == std::string_view::npos ? bytes_.size() : end;
    std::string_view line = bytes_.substr(position_, stop - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = std::min(stop + 1, bytes_.size());  // a last line without '\n' ends the file
    ++line_;
    return line;
  }

  static std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (j > i) out.push_back(line.substr(i, j - i));
      i = j;
    }
    return out;
  }

  double asciiNumber(std::string_view token) const {
    if (token == "nan" || token == "NaN" || token == "-nan") return std::nan("");
    double value = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size()) {
      failLine("not a number: " + printable(token));
    }
    return value;
  }

  std::size_t asciiCount(std::string_view token, const char* what) const {
    std::size_t value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size()) {
      failLine(std::string(what) + " must be a non-negative integer, got " + printable(token));
    }
    return value;
  }

  static const PcdField* find(const PcdHeader& header, const char* name) {
    for (const auto& f : header.fields) {
      if (f.name == name) return &f;
    }
    return nullptr;
  }

  // The field-major bytes of DATA binary_compressed: two little-endian uint32 (compressed and
  // uncompressed size) and LZF data, which must unpack to exactly n points.
  std::string decompress(const PcdHeader& header, std::size_t n) const {
    const std::string_view data = bytes_.substr(position_);
    if (data.size() < 8) {
      fail("data: binary_compressed needs 8 bytes of sizes, the file holds " +
           std::to_string(data.size()));
    }
    std::uint32_t sizes[2];
    std::memcpy(sizes, data.data(), sizeof sizes);
    const std::size_t compressed = sizes[0], raw = sizes[1];
    if (compressed > data.size() - 8) {
      fail("data: " + std::to_string(compressed) + " compressed bytes announced, the file holds " +
           std::to_string(data.size() - 8));
    }
    if (n > kMaxCompressedBytes / header.point_bytes || raw != n * header.point_bytes) {
      fail("data: " + std::to_string(n) + " points need " + std::to_string(n * header.point_bytes) +
           " bytes, the file unpacks to " + std::to_string(raw));
    }
    std::string columns(raw, '\0');
    if (raw == 0) return columns;
    const unsigned unpacked =
        lzf_decompress(data.data() + 8, unsigned(compressed), columns.data(), unsigned(raw));
    if (unpacked != raw) {
      fail("data: the LZF data is damaged (unpacks to " + std::to_string(unpacked) + " of " +
           std::to_string(raw) + " bytes)");
    }
    return columns;
  }

  // The value of field f stored at `at`.
  static double binaryValue(const char* at, const PcdField& f) {
    auto read = [at]<typename T>(T) {
      T v;
      std::memcpy(&v, at, sizeof v);
      return double(v);
    };
    switch (f.type) {
      case 'F':
        return f.size == 4 ? read(float{}) : read(double{});
      case 'U':
        switch (f.size) {
          case 1:
            return read(std::uint8_t{});
          case 2:
            return read(std::uint16_t{});
          case 4:
            return read(std::uint32_t{});
          default:
            return read(std::uint64_t{});
        }
      default:
        switch (f.size) {
          case 1:
            return read(std::int8_t{});
          case 2:
            return read(std::int16_t{});
          case 4:
            return read(std::int32_t{});
          default:
            return read(std::int64_t{});
        }
    }
  }

  PcdHeader readHeader() {
    PcdHeader header;
    std::vector<std::string_view> sizes, types, counts;
    bool have_width = false;
    while (header.data.empty()) {
      const std::string_view line = nextLine();
      if (line.data() == nullptr) {
        fail(line_ == 0 ? "empty file, not a PCD file"
                        : "header ends at line " + std::to_string(line_) + " without DATA");
      }
      if (line.empty() || line.front() == '#') continue;
      const auto tokens = split(line);
      if (tokens.empty()) continue;
      const std::string_view key = tokens.front();
      const std::vector<std::string_view> args(tokens.begin() + 1, tokens.end());
      if (key == "VERSION" || key == "VIEWPOINT") {
        continue;
      } else if (key == "FIELDS") {
        for (auto a : args) header.fields.push_back({std::string(a)});
      } else if (key == "SIZE") {
        sizes = args;
      } else if (key == "TYPE") {
        types = args;
      } else if (key == "COUNT") {
        counts = args;
      } else if (key == "WIDTH" && args.size() == 1) {
        header.width = asciiCount(args[0], "WIDTH");
        have_width = true;
      } else if (key == "HEIGHT" && args.size() == 1) {
        header.height = asciiCount(args[0], "HEIGHT");
      } else if (key == "POINTS" && args.size() == 1) {
        header.points = asciiCount(args[0], "POINTS");
      } else if (key == "DATA" && args.size() == 1) {
        header.data = std::string(args[0]);
        if (header.data != "binary" && header.data != "ascii" &&
            header.data != "binary_compressed") {
          failLine("unknown DATA " + printable(header.data) +
                   " (expected ascii, binary or binary_compressed)");
        }
      } else {
        failLine("not a PCD header line: " + printable(line));
      }
    }
    if (header.fields.empty()) failHeader("no FIELDS line");
    if (!have_width) failHeader("no WIDTH line");
    if (sizes.size() != header.fields.size() || types.size() != header.fields.size()) {
      failHeader("SIZE and TYPE must give one entry for each of the " +
                 std::to_string(header.fields.size()) + " FIELDS");
    }
    if (!counts.empty() && counts.size() != header.fields.size()) {
      failHeader("COUNT must give one entry for each of the " +
                 std::to_string(header.fields.size()) + " FIELDS");
    }
    for (std::size_t i = 0; i < header.fields.size(); ++i) {
      PcdField& f = header.fields[i];
      const std::size_t size = asciiCount(sizes[i], "SIZE");
      f.type = types[i].size() == 1 ? types[i][0] : '?';
      f.count =
          counts.empty() ? 1 : int(std::min<std::size_t>(asciiCount(counts[i], "COUNT"), 1u << 20));
      const bool valid =
          (f.type == 'F' && (size == 4 || size == 8)) ||
          ((f.type == 'U' || f.type == 'I') && (size == 1 || size == 2 || size == 4 || size == 8));
      if (!valid) {
        failHeader("field " + printable(f.name) + " has TYPE " + printable(types[i]) + " SIZE " +
                   printable(sizes[i]) + ", not a PCD number type");
      }
      if (f.count < 1) failHeader("field " + f.name + " has COUNT 0");
      f.size = int(size);
      f.offset = header.point_bytes;
      f.column = header.tokens_per_point;
      header.point_bytes += size * std::size_t(f.count);
      header.tokens_per_point += std::size_t(f.count);
      const bool used = f.name == "x" || f.name == "y" || f.name == "z" || f.name == "time" ||
                        f.name == "intensity" || f.name == "ring";
      if (used && f.count != 1) failHeader("field " + f.name + " must have COUNT 1");
    }
    if (header.height == 0 ||
        header.width > std::numeric_limits<std::size_t>::max() / header.height) {
      failHeader("WIDTH × HEIGHT is not a point count");
    }
    const std::size_t n = header.width * header.height;
    if (header.points && *header.points != n) {
      failHeader("POINTS " + std::to_string(*header.points) +
                 " is not WIDTH × HEIGHT = " + std::to_string(n));
    }
    return header;
  }

  std::string_view bytes_;
  const std::string& file_;
  std::size_t position_ = 0;
  std::size_t line_ = 0;
};

}  // namespace

std::vector<sensors::ScanPoint> parsePcd(std::string_view bytes, const std::string& file) {
  return PcdParser(bytes, file).parse();
}

std::vector<sensors::ScanPoint> readPcd(const std::string& path) {
  return parsePcd(common::readCheckedFile(path, kMaxPcdBytes), path);
}

PcdColumns parsePcdColumns(std::string_view bytes, const std::string& file) {
  return PcdParser(bytes, file).columns();
}

PcdColumns readPcdColumns(const std::string& path) {
  return parsePcdColumns(common::readCheckedFile(path, kMaxPcdBytes), path);
}

const std::vector<double>& PcdColumns::operator[](std::string_view name) const {
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) return values[k];
  }
  throw std::out_of_range("no PCD field " + std::string(name));
}

}  // namespace isg::formats
