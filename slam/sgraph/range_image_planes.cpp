#include "slam/sgraph/range_image_planes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>

#include "slam/sgraph/plane_fit.hpp"
#include "slam/sgraph/voxel_key.hpp"

namespace isg::slam {

namespace {

constexpr int kMinRings = 4;
constexpr int kMaxRings = 128;  // more rows than any spinning LiDAR has: not rings

// The scan as an image: rows are rings (by elevation), columns azimuth bins. Each cell holds the
// mean of its points and the points themselves (CSR).
struct RangeImage {
  int rows = 0, cols = 0;
  std::vector<Eigen::Vector3d> points;  // cropped, in the scan's frame
  std::vector<int> first;               // points of cell k: order[first[k] .. first[k + 1])
  std::vector<int> order;
  std::vector<Eigen::Vector3d> mean;
  std::vector<double> range;      // |mean|
  std::vector<double> ring_step;  // elevation from row r to row r + 1, radians
  int cell(int r, int c) const { return r * cols + c; }
  bool valid(int k) const { return first[k + 1] > first[k]; }
};

// Rows must follow elevation for the image's up and down neighbours to be the beams above and
// below. Drivers number rings differently (Velodyne's from the lowest beam, Ouster's and Hesai's
// from the top, raw laser ids in firing order), so the rings seen are ranked by their points' mean
// elevation and take the seen rows in that order; rings already in order keep their rows.
void reorderRowsByElevation(const std::vector<int>& ring_points,
                            const std::vector<double>& sine_sum, int cols,
                            std::vector<int>& cell_of) {
  std::vector<int> rings;  // seen, by number
  std::vector<double> mean(ring_points.size(), 0.0);
  for (int r = 0; r < int(ring_points.size()); ++r) {
    if (ring_points[std::size_t(r)] == 0) continue;
    rings.push_back(r);
    mean[std::size_t(r)] = sine_sum[std::size_t(r)] / ring_points[std::size_t(r)];
  }
  std::vector<int> by_elevation = rings;
  std::stable_sort(by_elevation.begin(), by_elevation.end(),
                   [&](int a, int b) { return mean[std::size_t(a)] < mean[std::size_t(b)]; });
  if (by_elevation == rings) return;
  std::vector<int> row_of(ring_points.size(), 0);
  for (std::size_t i = 0; i < rings.size(); ++i) row_of[std::size_t(by_elevation[i])] = rings[i];
  for (int& k : cell_of) k = row_of[std::size_t(k / cols)] * cols + k % cols;
}

std::optional<RangeImage> buildImage(const sensors::Scan& scan,
                                     const PlaneExtractionOptions& options) {
  RangeImage image;
  const double lo2 = options.min_range * options.min_range;
  const double hi2 = options.max_range * options.max_range;
  std::vector<int> cell_of;
  int max_ring = -1;
  std::vector<char> seen(kMaxRings, 0);
  std::vector<double> sine_sum(kMaxRings, 0.0);  // of the points' elevations, per ring
  std::vector<int> ring_points(kMaxRings, 0);
  image.cols = std::max(8, int(std::lround(360.0 / options.image_column_deg)));
  image.points.reserve(scan.points.size());
  cell_of.reserve(scan.points.size());
  for (const auto& p : scan.points) {
    const double r2 = double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
    if (r2 < lo2 || r2 > hi2) continue;
    if (p.ring >= kMaxRings) return std::nullopt;
    const double azimuth = std::atan2(double(p.y), double(p.x));  // (-π, π]
    int c = int((azimuth + std::numbers::pi) / (2 * std::numbers::pi) * image.cols);
    c = std::clamp(c, 0, image.cols - 1);
    image.points.emplace_back(p.x, p.y, p.z);
    cell_of.push_back(int(p.ring) * image.cols + c);
    max_ring = std::max(max_ring, int(p.ring));
    seen[p.ring] = 1;
    sine_sum[p.ring] += double(p.z) / std::sqrt(r2);
    ++ring_points[p.ring];
  }
  if (std::count(seen.begin(), seen.end(), 1) < kMinRings) return std::nullopt;
  image.rows = max_ring + 1;
  reorderRowsByElevation(ring_points, sine_sum, image.cols, cell_of);
  const int cells = image.rows * image.cols;
  image.first.assign(cells + 1, 0);
  for (int k : cell_of) ++image.first[k + 1];
  for (int k = 0; k < cells; ++k) image.first[k + 1] += image.first[k];
  image.order.resize(cell_of.size());
  std::vector<int> fill(image.first.begin(), image.first.end() - 1);
  for (int i = 0; i < int(cell_of.size()); ++i) image.order[fill[cell_of[i]]++] = i;
  image.mean.assign(cells, Eigen::Vector3d::Zero());
  image.range.assign(cells, 0.0);
  std::vector<double> elevation_sum(image.rows, 0.0);
  std::vector<int> elevation_count(image.rows, 0);
  for (int k = 0; k < cells; ++k) {
    if (!image.valid(k)) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = image.first[k]; i < image.first[k + 1]; ++i) sum += image.points[image.order[i]];
    image.mean[k] = sum / double(image.first[k + 1] - image.first[k]);
    image.range[k] = image.mean[k].norm();
    const int r = k / image.cols;
    elevation_sum[r] += std::atan2(image.mean[k].z(), image.mean[k].head<2>().norm());
    ++elevation_count[r];
  }
  // The rings' spacing in elevation, from the data (2° on a VLP-16); rows without points take
  // their neighbours' spacing.
  image.ring_step.assign(image.rows, 0.0);
  double fallback = 0.0;
  for (int r = 0; r + 1 < image.rows; ++r) {
    if (elevation_count[r] > 0 && elevation_count[r + 1] > 0) {
      image.ring_step[r] = std::abs(elevation_sum[r + 1] / elevation_count[r + 1] -
                                    elevation_sum[r] / elevation_count[r]);
      fallback = std::max(fallback, image.ring_step[r]);
    }
  }
  for (auto& step : image.ring_step) {
    if (step == 0.0) step = fallback;
  }
  return image;
}

// Running sums of weighted points, for a region's least-squares plane.
struct PlaneSums {
  double weight = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  void add(const Eigen::Vector3d& p, double w) {
    weight += w;
    sum += w * p;
    outer += w * p * p.transpose();
  }
  void add(const PlaneSums& other) {
    weight += other.weight;
    sum += other.sum;
    outer += other.outer;
  }
  Eigen::Vector3d centroid() const { return sum / weight; }
  Eigen::Vector3d normal() const {
    const Eigen::Vector3d c = centroid();
    const Eigen::Matrix3d covariance = outer / weight - c * c.transpose();
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  }
};

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// The number of distinct `voxel`-sized cells the points fall in: the support RANSAC on a
// voxel-filtered cloud would count, whatever the points' density.
int voxelSupport(const std::vector<Eigen::Vector3d>& points, double voxel) {
  std::vector<std::uint64_t> keys;
  keys.reserve(points.size());
  for (const auto& p : points) keys.push_back(voxelKey(p, voxel));
  std::sort(keys.begin(), keys.end());
  return int(std::unique(keys.begin(), keys.end()) - keys.begin());
}

// A wall's top edge from the cells above its highest cell in each column: the first return above
// it farther than the wall by more than `margin` went over the wall (its top is seen there); one
// nearer by more than `margin` met something in front of the wall's continuation (the ceiling);
// none above because the rings ran out means the top is beyond the sensor's view. The majority
// of the columns that tell decides, with at least kMinTellingColumns of them. A vertical wall's
// points in one azimuth column all lie at one horizontal distance, which is what is compared.
TopEdge topEdgeOf(const RangeImage& image, const std::vector<int>& cells, double margin) {
  constexpr int kMinTellingColumns = 3;
  constexpr int kRowsToLookUp = 2;              // a lost return just above the wall is skipped
  std::vector<std::pair<int, int>> column_row;  // (column, row) of every cell
  column_row.reserve(cells.size());
  for (int k : cells) column_row.emplace_back(k % image.cols, k / image.cols);
  std::sort(column_row.begin(), column_row.end());
  int over = 0, beyond = 0;
  for (std::size_t i = 0; i < column_row.size(); ++i) {
    if (i + 1 < column_row.size() && column_row[i + 1].first == column_row[i].first) continue;
    const auto [c, r] = column_row[i];  // the column's highest cell on the wall
    if (r + 1 >= image.rows) {
      ++beyond;
      continue;
    }
    const double wall = image.mean[image.cell(r, c)].head<2>().norm();
    for (int up = r + 1; up < std::min(image.rows, r + 1 + kRowsToLookUp); ++up) {
      const int k = image.cell(up, c);
      if (!image.valid(k)) continue;
      const double above = image.mean[k].head<2>().norm();
      if (above > wall + margin) ++over;
      if (above < wall - margin) ++beyond;
      break;
    }
  }
  if (std::max(over, beyond) < kMinTellingColumns) return TopEdge::kUnknown;
  return over > beyond ? TopEdge::kSeen : TopEdge::kBeyondView;
}

// Which cells of the image neighbour each other on one surface.
struct Neighbours {
  const RangeImage& image;
  const PlaneExtractionOptions& options;

  // Two cells are neighbours on one surface only when close: along a ring within the cluster
  // tolerance; across rings within that or a few times the rings' spacing at that range (so that
  // a floor, seen at a grazing angle, stays one surface).
  bool close(int a, int b, bool across_rings) const {
    if (!image.valid(a) || !image.valid(b)) return false;
    double limit = options.cluster_tolerance;
    if (across_rings) {
      const int r0 = std::min(a / image.cols, b / image.cols);
      const int r1 = std::max(a / image.cols, b / image.cols);
      double step = 0.0;
      for (int r = r0; r < r1; ++r) step += image.ring_step[r];
      limit = std::max(limit,
                       options.ring_gap_factor * std::min(image.range[a], image.range[b]) * step);
    }
    return (image.mean[a] - image.mean[b]).squaredNorm() <= limit * limit;
  }
  // The cell across the rings (`direction` +1 up, −1 down) a cell's normal is taken to: in the
  // nearest row at least an image column's width of elevation away, so that the normal's two
  // baselines are alike. Rings 0.35° apart (an OS1-128) next to columns 0.8° wide would give a
  // baseline across a fifth of the one along, and a normal that the range noise turns by tens of
  // degrees: the regions would break into thousands. Where that row's cell is missing or not
  // close, the nearest nearer one that is; -1 for none. Rings 2° apart (a VLP-16): the next row.
  int acrossForNormal(int k, int direction) const {
    const int r = k / image.cols, c = k % image.cols;
    const double wanted = options.image_column_deg * std::numbers::pi / 180.0;
    double step = 0.0;
    int far = r;
    while (step < wanted) {
      const int next = far + direction;
      if (next < 0 || next >= image.rows) break;
      step += image.ring_step[std::min(far, next)];
      far = next;
    }
    for (int q = far; q != r; q -= direction) {
      if (close(k, image.cell(q, c), true)) return image.cell(q, c);
    }
    return -1;
  }
  int left(int k) const { return k % image.cols == 0 ? k + image.cols - 1 : k - 1; }
  int right(int k) const { return k % image.cols == image.cols - 1 ? k - image.cols + 1 : k + 1; }
};

// Each cell's normal from its neighbours' means: the cross product of the differences along the
// ring and across the rings (one-sided where a neighbour is missing or far), towards the sensor.
void cellNormals(const Neighbours& near, std::vector<Eigen::Vector3d>& normal,
                 std::vector<char>& has_normal) {
  const RangeImage& image = near.image;
  const int rows = image.rows, cols = image.cols, cells = rows * cols;
  normal.assign(cells, Eigen::Vector3d::Zero());
  has_normal.assign(cells, 0);
  for (int k = 0; k < cells; ++k) {
    if (!image.valid(k)) continue;
    const int l = near.left(k), rr = near.right(k);
    const int down = near.acrossForNormal(k, -1), up = near.acrossForNormal(k, +1);
    const bool has_l = near.close(k, l, false), has_r = near.close(k, rr, false);
    const bool has_d = down >= 0, has_u = up >= 0;
    if ((!has_l && !has_r) || (!has_d && !has_u)) continue;
    const Eigen::Vector3d along = image.mean[has_r ? rr : k] - image.mean[has_l ? l : k];
    const Eigen::Vector3d across = image.mean[has_u ? up : k] - image.mean[has_d ? down : k];
    Eigen::Vector3d n = along.cross(across);
    const double norm = n.norm();
    if (norm < 1e-12) continue;
    n /= norm;
    if (n.dot(image.mean[k]) > 0) n = -n;  // towards the sensor
    normal[k] = n;
    has_normal[k] = 1;
  }
}

// Region growing: from each unlabelled cell with a normal, to neighbours that are close, lie
// within the plane distance of the region's plane and (when they have a normal) turn alike.
// Returns each region's sums; `label` the region of each cell (-1: none).
std::vector<PlaneSums> growRegions(const Neighbours& near,
                                   const std::vector<Eigen::Vector3d>& normal,
                                   const std::vector<char>& has_normal, std::vector<int>& label) {
  const RangeImage& image = near.image;
  const PlaneExtractionOptions& options = near.options;
  const int rows = image.rows, cols = image.cols, cells = rows * cols;
  const double cos_angle = std::cos(options.normal_angle_deg * std::numbers::pi / 180.0);
  label.assign(cells, -1);
  std::vector<PlaneSums> sums;
  std::vector<int> queue;
  queue.reserve(cells);
  for (int seed = 0; seed < cells; ++seed) {
    if (!has_normal[seed] || label[seed] >= 0) continue;
    const int region = int(sums.size());
    sums.emplace_back();
    PlaneSums& s = sums.back();
    Eigen::Vector3d n = normal[seed];
    double d = -n.dot(image.mean[seed]);
    double refit_at = 3.0;
    auto take = [&](int k) {
      label[k] = region;
      s.add(image.mean[k], double(image.first[k + 1] - image.first[k]));
      queue.push_back(k);
    };
    queue.clear();
    take(seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int k = queue[head];
      const int r = k / cols;
      const int neighbours[4] = {near.left(k), near.right(k), r > 0 ? k - cols : -1,
                                 r + 1 < rows ? k + cols : -1};
      for (int i = 0; i < 4; ++i) {
        const int q = neighbours[i];
        if (q < 0 || label[q] >= 0 || !near.close(k, q, i >= 2)) continue;
        if (std::abs(n.dot(image.mean[q]) + d) > options.ransac_distance) continue;
        if (has_normal[q] && std::abs(normal[q].dot(n)) < cos_angle) continue;
        take(q);
      }
      if (double(queue.size()) >= refit_at) {
        n = s.normal();
        d = -n.dot(s.centroid());
        refit_at *= 2;
      }
    }
  }
  return sums;
}

// Regions that touch and lie on one plane are one surface (growth can stop at a noisy cell): the
// root of each region's surface, in `parent`.
std::vector<int> mergeCoplanar(const Neighbours& near, const std::vector<PlaneSums>& sums,
                               const std::vector<int>& label) {
  const RangeImage& image = near.image;
  const PlaneExtractionOptions& options = near.options;
  const int rows = image.rows, cols = image.cols, cells = rows * cols;
  const int regions = int(sums.size());
  std::vector<int> parent(regions);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<Eigen::Vector3d> region_normal(regions), region_centroid(regions);
  for (int g = 0; g < regions; ++g) {
    region_normal[g] = sums[g].normal();
    region_centroid[g] = sums[g].centroid();
  }
  const double cos_merge = std::cos(options.merge_angle_deg * std::numbers::pi / 180.0);
  auto coplanar = [&](int a, int b) {
    if (std::abs(region_normal[a].dot(region_normal[b])) < cos_merge) return false;
    return std::abs(region_normal[a].dot(region_centroid[b] - region_centroid[a])) <=
               options.ransac_distance &&
           std::abs(region_normal[b].dot(region_centroid[a] - region_centroid[b])) <=
               options.ransac_distance;
  };
  for (int k = 0; k < cells; ++k) {
    if (label[k] < 0) continue;
    const int r = k / cols;
    const int neighbours[2] = {near.right(k), r + 1 < rows ? k + cols : -1};
    for (int i = 0; i < 2; ++i) {
      const int q = neighbours[i];
      if (q < 0 || label[q] < 0 || label[q] == label[k]) continue;
      const int a = findRoot(parent, label[k]), b = findRoot(parent, label[q]);
      if (a == b || !near.close(k, q, i == 1) || !coplanar(label[k], label[q])) continue;
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  return parent;
}

// Each surface: least squares on its points, then again on those within the plane distance;
// kept with enough support (horizontal surfaces need less: PlaneExtractionOptions).
std::vector<PlaneObservation> fitSurfaces(const RangeImage& image,
                                          const std::vector<std::vector<int>>& members,
                                          const PlaneExtractionOptions& options) {
  std::vector<PlaneObservation> planes;
  std::vector<Eigen::Vector3d> points, inliers;
  for (const auto& cells : members) {
    if (cells.empty()) continue;
    points.clear();
    for (int k : cells) {
      for (int i = image.first[k]; i < image.first[k + 1]; ++i)
        points.push_back(image.points[image.order[i]]);
    }
    const int least = std::min(options.min_inliers, options.horizontal_min_inliers);
    if (int(points.size()) < least) continue;
    PlaneSums all;
    for (const auto& p : points) all.add(p, 1.0);
    const Eigen::Vector3d n = all.normal(), c = all.centroid();
    inliers.clear();
    for (const auto& p : points) {
      if (std::abs(n.dot(p - c)) <= options.ransac_distance) inliers.push_back(p);
    }
    if (int(inliers.size()) < least) continue;
    const int support = voxelSupport(inliers, options.voxel);
    if (support < least) continue;
    planes.push_back(observePlane(inliers, support, options));
    if (support < options.min_inliers &&
        planes.back().orientation != PlaneOrientation::kHorizontal) {
      planes.pop_back();
      continue;
    }
    if (planes.back().orientation == PlaneOrientation::kVertical)
      planes.back().top = topEdgeOf(image, cells, options.cluster_tolerance);
  }
  return planes;
}

}  // namespace

std::optional<std::vector<PlaneObservation>> extractPlanesOnRangeImage(
    const sensors::Scan& scan, const PlaneExtractionOptions& options) {
  const auto built = buildImage(scan, options);
  if (!built) return std::nullopt;
  const RangeImage& image = *built;
  const Neighbours near{image, options};
  std::vector<Eigen::Vector3d> normal;
  std::vector<char> has_normal;
  cellNormals(near, normal, has_normal);
  std::vector<int> label;
  const std::vector<PlaneSums> sums = growRegions(near, normal, has_normal, label);
  std::vector<int> parent = mergeCoplanar(near, sums, label);
  std::vector<std::vector<int>> members(sums.size());
  for (int k = 0; k < image.rows * image.cols; ++k) {
    if (label[k] >= 0) members[findRoot(parent, label[k])].push_back(k);
  }
  std::vector<PlaneObservation> planes = fitSurfaces(image, members, options);
  std::stable_sort(
      planes.begin(), planes.end(),
      [](const PlaneObservation& a, const PlaneObservation& b) { return a.points > b.points; });
  if (int(planes.size()) > options.max_planes) planes.resize(options.max_planes);
  return planes;
}

}  // namespace isg::slam
