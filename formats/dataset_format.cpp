#include "formats/dataset_format.hpp"

#include <lzf.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/tum.hpp"

namespace isg::formats::dataset {

std::string scanFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.pcd", index);
  return name;
}

std::optional<double> meanPeriod(const std::vector<double>& stamps) {
  if (stamps.size() < 2) return std::nullopt;
  return (stamps.back() - stamps.front()) / double(stamps.size() - 1);
}

std::string trajectoryText(const common::Trajectory& trajectory) {
  return common::toTumText(trajectory);
}

std::string stampsText(const std::vector<double>& stamps) {
  std::string out;
  char line[64];
  for (double t : stamps) {
    std::snprintf(line, sizeof line, "%.9f\n", t);
    out += line;
  }
  return out;
}

std::string imuText(const std::vector<sensors::ImuSample>& samples) {
  std::string out = "t,ax,ay,az,gx,gy,gz\n";
  out.reserve(out.size() + samples.size() * 120);
  char line[256];
  for (const auto& s : samples) {
    const Eigen::Vector3d& a = s.accelerometer;
    const Eigen::Vector3d& g = s.gyroscope;
    const int n = std::snprintf(line, sizeof line, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s.t,
                                a.x(), a.y(), a.z(), g.x(), g.y(), g.z());
    out.append(line, std::size_t(n));
  }
  return out;
}

const char* pcdDataName(PcdData data) {
  return data == PcdData::kBinary ? "binary" : "binary_compressed";
}

namespace {

// Appends `bytes` to `out` as LZF. An LZF stream is a sequence of tokens whose back references
// never reach before the start of the text they encode, so streams of consecutive pieces
// concatenate into the stream of the whole. That lets each field choose: the noisy mantissas of
// x, y and time do not compress (LZF leaves them at 100-103 % of their size, at ~200 MB/s), so a
// field whose first kProbeBytes do not shrink below kWorthIt is stored as literal runs (a control
// byte 0-31 and that many plus one bytes: +3 %, at memcpy speed) and the rest is compressed.
void appendLzf(std::string& out, const std::string& bytes) {
  constexpr std::size_t kProbeBytes = 4096;
  constexpr double kWorthIt = 0.9;
  const std::size_t probe = std::min(bytes.size(), kProbeBytes);
  char probe_out[kProbeBytes];
  const unsigned probed =
      probe == 0 ? 0 : lzf_compress(bytes.data(), unsigned(probe), probe_out, unsigned(probe));
  // lzf_compress returns 0 when the result would not fit in `probe` bytes: no gain at all.
  if (probe > 0 && probed > 0 && probed < kWorthIt * probe) {
    // Compressed straight into `out`: LZF's worst case is 1 control byte per 32 literals.
    const std::size_t at = out.size();
    const std::size_t bound = bytes.size() + bytes.size() / 32 + 64;
    out.resize(at + bound);
    const unsigned size =
        lzf_compress(bytes.data(), unsigned(bytes.size()), out.data() + at, unsigned(bound));
    if (size == 0) throw std::runtime_error("PCD: LZF compression failed");
    out.resize(at + size);
    return;
  }
  constexpr std::size_t kLiteralRun = 32;  // LZF's longest literal run
  for (std::size_t i = 0; i < bytes.size(); i += kLiteralRun) {
    const std::size_t run = std::min(kLiteralRun, bytes.size() - i);
    out.push_back(char(run - 1));
    out.append(bytes.data() + i, run);
  }
}

}  // namespace

std::string pcdBytes(const std::vector<sensors::ScanPoint>& points, PcdData data) {
  const std::size_t n = points.size();
  std::string out =
      "# .PCD v0.7 - Point Cloud Data file format\n"
      "VERSION 0.7\n"
      "FIELDS x y z intensity ring time\n"
      "SIZE 4 4 4 4 2 4\n"
      "TYPE F F F F U F\n"
      "COUNT 1 1 1 1 1 1\n"
      "WIDTH " +
      std::to_string(n) +
      "\n"
      "HEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\n"
      "POINTS " +
      std::to_string(n) + "\nDATA " + pcdDataName(data) + "\n";
  constexpr std::size_t kPointBytes = 22;
  const std::size_t header = out.size();
  const std::size_t raw = n * kPointBytes;
  // Each field copied with its size known to the compiler: a memcpy of 4 or 2 bytes is a move,
  // one of a size known only at run time a library call (half the encoder's time).
  auto field = [&points, n]<typename T>(T sensors::ScanPoint::*member, char* at,
                                        std::size_t stride) {
    for (std::size_t i = 0; i < n; ++i, at += stride)
      std::memcpy(at, &(points[i].*member), sizeof(T));
  };
  auto each_field = [](auto&& f) {
    f(&sensors::ScanPoint::x);
    f(&sensors::ScanPoint::y);
    f(&sensors::ScanPoint::z);
    f(&sensors::ScanPoint::intensity);
    f(&sensors::ScanPoint::ring);
    f(&sensors::ScanPoint::time);
  };
  if (data == PcdData::kBinary) {
    // Point after point.
    out.resize(header + raw);
    std::size_t offset = header;
    each_field([&]<typename T>(T sensors::ScanPoint::*member) {
      field(member, out.data() + offset, kPointBytes);
      offset += sizeof(T);
    });
    return out;
  }
  // Field after field (all x, then all y, ...) as one LZF stream, behind two little-endian
  // uint32: the compressed and the uncompressed size (PCL's layout, read by PCL and its tools).
  out.reserve(header + 8 + raw + raw / 32 + 6 * 64);
  out.resize(header + 8);
  std::string column;
  each_field([&]<typename T>(T sensors::ScanPoint::*member) {
    column.resize(n * sizeof(T));
    field(member, column.data(), sizeof(T));
    appendLzf(out, column);
  });
  const std::uint32_t sizes[2] = {std::uint32_t(out.size() - header - 8), std::uint32_t(raw)};
  std::memcpy(out.data() + header, sizes, sizeof sizes);
  return out;
}

nlohmann::ordered_json mountJson(const std::array<double, 6>& xyz_rpy, const Eigen::Isometry3d& T) {
  const Eigen::Matrix4d M = T.matrix();
  nlohmann::ordered_json matrix = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) matrix.push_back({M(r, 0), M(r, 1), M(r, 2), M(r, 3)});
  return {{"xyz_rpy", xyz_rpy}, {"matrix", matrix}};
}

nlohmann::ordered_json extrinsicsJson(const std::array<double, 6>& xyz_rpy,
                                      const Eigen::Isometry3d& R_T_L) {
  return {{"R_T_L", mountJson(xyz_rpy, R_T_L)}};
}

}  // namespace isg::formats::dataset
