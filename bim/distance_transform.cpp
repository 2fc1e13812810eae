#include "bim/distance_transform.hpp"

#include <limits>

namespace isg::bim {

namespace {

// Squared distance transform of one line of samples f: d[q] = min_p (q - p)² + f[p], from the
// lower envelope of the parabolas rooted at each p.
void distanceTransform1d(const std::vector<double>& f, std::vector<double>& d) {
  const int n = int(f.size());
  if (n == 0) return;
  std::vector<int> v(n);
  std::vector<double> z(n + 1);
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  auto intersection = [&](int q, int r) {
    return ((f[q] + double(q) * q) - (f[r] + double(r) * r)) / (2.0 * q - 2.0 * r);
  };
  for (int q = 1; q < n; ++q) {
    double s = intersection(q, v[k]);
    while (s <= z[k]) s = intersection(q, v[--k]);  // z[0] = -inf ends the loop
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = (q - v[k]) * double(q - v[k]) + f[v[k]];
  }
}

}  // namespace

std::vector<double> squaredDistanceTransform(const std::vector<char>& source, int width,
                                             int height) {
  constexpr double kFar = 1e12;
  std::vector<double> field(std::size_t(width) * height);
  for (std::size_t i = 0; i < field.size(); ++i) field[i] = source[i] ? 0.0 : kFar;
  std::vector<double> line(height), out(height);
  for (int x = 0; x < width; ++x) {
    for (int y = 0; y < height; ++y) line[y] = field[std::size_t(y) * width + x];
    distanceTransform1d(line, out);
    for (int y = 0; y < height; ++y) field[std::size_t(y) * width + x] = out[y];
  }
  line.resize(width);
  out.resize(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) line[x] = field[std::size_t(y) * width + x];
    distanceTransform1d(line, out);
    for (int x = 0; x < width; ++x) field[std::size_t(y) * width + x] = out[x];
  }
  return field;
}

}  // namespace isg::bim
