#include "run/dataset_format.hpp"

#include <cstdio>
#include <cstring>

namespace isg::run::dataset {

namespace {

template <typename T>
void append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

std::string scanFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.pcd", index);
  return name;
}

std::string trajectoryText(const Trajectory& trajectory) { return eval::toTumText(trajectory); }

std::string pcdBinary(const std::vector<slam::ScanPoint>& points) {
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
      std::to_string(n) +
      "\n"
      "DATA binary\n";
  out.reserve(out.size() + n * 22);
  for (const auto& p : points) {
    append(out, p.x);
    append(out, p.y);
    append(out, p.z);
    append(out, p.intensity);
    append(out, p.ring);
    append(out, p.time);
  }
  return out;
}

nlohmann::ordered_json extrinsicsJson(const std::array<double, 6>& xyz_rpy,
                                      const Eigen::Isometry3d& R_T_L) {
  const Eigen::Matrix4d T = R_T_L.matrix();
  nlohmann::ordered_json matrix = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) matrix.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return {{"R_T_L", {{"xyz_rpy", xyz_rpy}, {"matrix", matrix}}}};
}

}  // namespace isg::run::dataset
