#include "common/tum.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "common/decimal_number.hpp"

namespace isg::common {

std::string toTumText(std::span<const StampedPose> trajectory) {
  std::string out;
  out.reserve(trajectory.size() * 100);
  char line[256];
  for (const auto& p : trajectory) {
    Eigen::Quaterniond q(p.pose.linear());
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1.0;
    const Eigen::Vector3d t = p.pose.translation();
    const auto row = [&](char* text, std::size_t size) {
      return std::snprintf(text, size, "%.9f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", p.t, t.x(),
                           t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
    };
    const int length = row(line, sizeof line);
    if (length < int(sizeof line)) {
      out += line;
    } else {  // a number of hundreds of digits: the row whole, never cut at the buffer's end
      std::string long_row(std::size_t(length) + 1, '\0');
      row(long_row.data(), long_row.size());
      long_row.pop_back();
      out += long_row;
    }
  }
  return out;
}

namespace {

// x·scale rounded to an integer as printf's "%.Nf" rounds x to N decimals (scale = 10^N): the
// exact binary value, ties to even. The integer N = round(x·10^k) is found from the product and
// its exact error (fma); N / scale is then what strtod reads back from that text (IEEE division
// is correctly rounded). Exact while |x|·scale < 2^53.
double decimalSteps(double x, double scale) {
  const double p = x * scale;
  double n = std::nearbyint(p);                 // ties to even on p; keeps the sign of zero
  const double error = std::fma(x, scale, -p);  // x·scale = p + error, exactly
  const double rest = p - n;                    // exact; only a half-way p can round wrongly
  if (rest == 0.5 && error > 0) n += 1.0;       // x·scale lies just above the half
  if (rest == -0.5 && error < 0) n -= 1.0;      // just below the negative half
  return n;
}

}  // namespace

double quantisedTime(double t) { return decimalSteps(t, 1e9) / 1e9; }

std::array<double, 3> tumPositionSteps(const Eigen::Vector3d& p) {
  return {decimalSteps(p.x(), 1e6), decimalSteps(p.y(), 1e6), decimalSteps(p.z(), 1e6)};
}

Eigen::Vector3d positionOfTumSteps(const std::array<double, 3>& steps) {
  return {steps[0] / 1e6, steps[1] / 1e6, steps[2] / 1e6};
}

Eigen::Vector3d quantisedPosition(const Eigen::Vector3d& p) {
  return positionOfTumSteps(tumPositionSteps(p));
}

std::array<double, 4> tumQuaternionSteps(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return {decimalSteps(q.w(), 1e9), decimalSteps(q.x(), 1e9), decimalSteps(q.y(), 1e9),
          decimalSteps(q.z(), 1e9)};
}

Eigen::Matrix3d rotationOfTumSteps(const std::array<double, 4>& steps) {
  const Eigen::Quaterniond read(steps[0] / 1e9, steps[1] / 1e9, steps[2] / 1e9, steps[3] / 1e9);
  return read.normalized().toRotationMatrix();
}

void quantise(Trajectory& trajectory) {
  for (auto& p : trajectory) {
    p.t = quantisedTime(p.t);
    p.pose.translation() = quantisedPosition(p.pose.translation());
    p.pose.linear() = rotationOfTumSteps(tumQuaternionSteps(p.pose.linear()));
    // What the parser makes of a TUM row: the bottom row exactly 0 0 0 1.
    p.pose.makeAffine();
  }
}

Trajectory quantised(const Trajectory& trajectory) {
  Trajectory out = trajectory;
  quantise(out);
  return out;
}

TumError::TumError(std::string file, int line, std::string reason)
    : std::runtime_error(file + ": " +
                         (line > 0 ? "line " + std::to_string(line) + ": " + reason : reason)),
      file_(std::move(file)),
      line_(line),
      reason_(std::move(reason)) {}

std::string TumError::located() const {
  return line_ > 0 ? "line " + std::to_string(line_) + ": " + reason_ : reason_;
}

Trajectory parseTum(const std::string& text, const std::string& file, std::vector<int>* lines) {
  Trajectory out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    double v[8];
    std::size_t at = first;
    const auto nextField = [&]() -> std::string_view {
      while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
      const std::size_t from = at;
      while (at < line.size() && line[at] != ' ' && line[at] != '\t' && line[at] != '\r') ++at;
      return std::string_view(line).substr(from, at - from);
    };
    for (int k = 0; k < 8; ++k) {
      const std::string_view field = nextField();
      if (field.empty()) throw TumError(file, number, "expected 8 numbers: t tx ty tz qx qy qz qw");
      const std::optional<double> value = parseDecimal(field);
      if (!value) {
        const std::string shown(field.substr(0, 40));
        throw TumError(file, number,
                       "field " + std::to_string(k + 1) + " (\"" + shown +
                           "\") is not a finite decimal number; expected 8 numbers: t tx ty tz "
                           "qx qy qz qw");
      }
      v[k] = *value;
    }
    if (!nextField().empty()) throw TumError(file, number, "more than 8 fields");
    const auto outOfRange = [&](const char* what, double value, const char* limit) {
      char message[160];
      std::snprintf(message, sizeof message, "%s %g is out of range (%s)", what, value, limit);
      throw TumError(file, number, message);
    };
    if (std::abs(v[0]) > kMaxTumTime) outOfRange("time", v[0], "|t| at most 1e10 s");
    for (int k = 1; k <= 3; ++k) {
      if (std::abs(v[k]) > kMaxTumCoordinate) {
        outOfRange(k == 1 ? "tx" : k == 2 ? "ty" : "tz", v[k], "at most 1e9 m from the origin");
      }
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw TumError(file, number, "quaternion is not unit length");
    }
    // Association and interpolation need time order; a file out of order is damaged.
    if (!out.empty() && !(v[0] > out.back().t)) {
      throw TumError(file, number,
                     "time " + std::to_string(v[0]) + " does not come after the previous pose's " +
                         std::to_string(out.back().t) + " (poses must be in increasing time)");
    }
    StampedPose p;
    p.t = v[0];
    p.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    p.pose.linear() = q.normalized().toRotationMatrix();
    out.push_back(p);
    if (lines != nullptr) lines->push_back(number);
  }
  return out;
}

Trajectory readTum(const std::string& path, std::vector<int>* lines) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw TumError(path, 0, "cannot open file");
  if (!std::filesystem::is_regular_file(status)) throw TumError(path, 0, "not a regular file");
  const auto bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > kMaxTumBytes) {
    throw TumError(path, 0,
                   "file is " + std::to_string(bytes) + " bytes; at most " +
                       std::to_string(kMaxTumBytes) + " are read");
  }
  std::ifstream in(path);
  if (!in) throw TumError(path, 0, "cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return parseTum(s.str(), path, lines);
}

}  // namespace isg::common
