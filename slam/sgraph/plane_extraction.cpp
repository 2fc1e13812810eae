#include "slam/sgraph/plane_extraction.hpp"
#include "common/angles.hpp"
#include "slam/sgraph/pcl_planes.hpp"
#include "slam/sgraph/plane_fit.hpp"
#include "slam/sgraph/range_image_planes.hpp"

#include <pcl/ModelCoefficients.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace isg::slam {

namespace {

// Where along a wall its inliers stand (PlaneExtractionOptions::wall_column_height), apart where
// they leave a hole (hole_columns): shares of out.start → out.end; empty when they stand over all
// of it, or nowhere. Sensor at the origin: a wall h off it is sampled, at horizontal range ρ,
// every ρ²·Δ/h along it for an azimuth step Δ.
std::vector<std::pair<double, double>> piecesAlong(const std::vector<Eigen::Vector3d>& points,
                                                   const Eigen::Vector3d& along,
                                                   const PlaneObservation& out,
                                                   const PlaneExtractionOptions& options) {
  std::vector<std::pair<double, double>> pieces;
  const double h = std::abs(out.plane.d);
  const double length = along.dot(out.end - out.start);
  if (h < 1e-3 || length <= options.cluster_tolerance) return pieces;
  struct Column {
    double z_min = 1e300, z_max = -1e300, s_min = 1e300, s_max = -1e300, range = 0.0;
  };
  const double width = options.wall_column_width;
  std::vector<Column> columns(std::size_t(length / width) + 1);
  for (const auto& p : points) {
    const double s = std::clamp(along.dot(p - out.start), 0.0, length);
    Column& c = columns[std::min(columns.size() - 1, std::size_t(s / width))];
    c.z_min = std::min(c.z_min, p.z());
    c.z_max = std::max(c.z_max, p.z());
    c.s_min = std::min(c.s_min, s);
    c.s_max = std::max(c.s_max, s);
    c.range = std::max(c.range, p.head<2>().norm());
  }
  const double step = common::radians(options.image_column_deg);
  const Column* last = nullptr;  // the last column the wall stands in
  for (const Column& c : columns) {
    if (c.z_max - c.z_min < options.wall_column_height) continue;
    const double gap = last ? c.s_min - last->s_max : 0.0;
    const double range = last ? std::max(c.range, last->range) : 0.0;
    if (!last || (gap > options.cluster_tolerance &&
                  gap > options.hole_columns * step * range * range / h)) {
      if (last) pieces.back().second = last->s_max;
      pieces.emplace_back(c.s_min, c.s_max);
    }
    last = &c;
  }
  if (pieces.empty()) return pieces;
  pieces.back().second = last->s_max;
  if (pieces.size() == 1 && pieces[0].first <= 0.0 && pieces[0].second >= length) return {};
  for (auto& [a, b] : pieces) {
    a /= length;
    b /= length;
  }
  return pieces;
}

}  // namespace

PlaneObservation observePlane(const std::vector<Eigen::Vector3d>& points, int support,
                              const PlaneExtractionOptions& options) {
  PlaneObservation out;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d normal = solver.eigenvectors().col(0);
  if (normal.dot(-mean) < 0) normal = -normal;  // towards the sensor
  out.plane = bim::Plane::throughPoint(normal, mean);
  out.centroid = mean;
  out.points = support;
  const double nz = std::abs(normal.z());
  out.orientation = nz < options.vertical_max_normal_z
                        ? PlaneOrientation::kVertical
                        : (nz > options.horizontal_min_normal_z ? PlaneOrientation::kHorizontal
                                                                : PlaneOrientation::kOblique);
  // Extent: along the in-plane horizontal direction, and in z.
  Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(normal);
  if (along.norm() < 1e-6) along = Eigen::Vector3d::UnitX();
  along.normalize();
  double lo = 1e300, hi = -1e300, sum2 = 0.0;
  out.z_min = 1e300;
  out.z_max = -1e300;
  for (const auto& p : points) {
    const double s = along.dot(p - mean);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
    out.z_min = std::min(out.z_min, p.z());
    out.z_max = std::max(out.z_max, p.z());
    const double d = out.plane.signedDistance(p);
    sum2 += d * d;
  }
  // Extent endpoints projected onto the plane, at the centroid's height.
  out.start = mean + lo * along;
  out.end = mean + hi * along;
  out.rms = std::sqrt(sum2 / double(points.size()));
  if (out.orientation == PlaneOrientation::kVertical)
    out.pieces = piecesAlong(points, along, out, options);
  return out;
}

namespace {

// The cluster's points as doubles, for observePlane.
std::vector<Eigen::Vector3d> pointsOf(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                      const std::vector<int>& indices) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(indices.size());
  for (int i : indices) out.push_back(cloud[i].getVector3fMap().cast<double>());
  return out;
}

}  // namespace

pcl::PointCloud<pcl::PointXYZ>::Ptr preprocess(const sensors::Scan& scan,
                                               const PlaneExtractionOptions& options) {
  auto cropped = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cropped->reserve(scan.points.size());
  const double lo2 = options.min_range * options.min_range;
  const double hi2 = options.max_range * options.max_range;
  for (const auto& p : scan.points) {
    const double r2 = double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
    if (r2 < lo2 || r2 > hi2) continue;
    cropped->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  }
  auto filtered = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(cropped);
  grid.setLeafSize(float(options.voxel), float(options.voxel), float(options.voxel));
  grid.filter(*filtered);
  return filtered;
}

std::vector<PlaneObservation> extractPlanes(const sensors::Scan& scan,
                                            const PlaneExtractionOptions& options) {
  if (options.method == PlaneExtractionOptions::Method::kRangeImage) {
    if (auto planes = extractPlanesOnRangeImage(scan, options)) return std::move(*planes);
  }
  return extractPlanes(*preprocess(scan, options), options);
}

std::vector<PlaneObservation> extractPlanes(const pcl::PointCloud<pcl::PointXYZ>& input,
                                            const PlaneExtractionOptions& options) {
  std::vector<PlaneObservation> planes;
  auto remaining = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>(input);
  pcl::SACSegmentation<pcl::PointXYZ> ransac;
  ransac.setOptimizeCoefficients(true);
  ransac.setModelType(pcl::SACMODEL_PLANE);
  ransac.setMethodType(pcl::SAC_RANSAC);
  ransac.setDistanceThreshold(options.ransac_distance);
  ransac.setMaxIterations(500);
  for (int round = 0; round < options.max_planes && int(remaining->size()) >= options.min_inliers;
       ++round) {
    pcl::PointIndices::Ptr inliers(new pcl::PointIndices);
    pcl::ModelCoefficients coefficients;
    ransac.setInputCloud(remaining);
    ransac.segment(*inliers, coefficients);
    if (int(inliers->indices.size()) < options.min_inliers) break;

    // Split the plane's inliers where they are apart.
    auto plane_cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    pcl::ExtractIndices<pcl::PointXYZ> extract;
    extract.setInputCloud(remaining);
    extract.setIndices(inliers);
    extract.setNegative(false);
    extract.filter(*plane_cloud);
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree->setInputCloud(plane_cloud);
    std::vector<pcl::PointIndices> clusters;
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> clustering;
    clustering.setClusterTolerance(options.cluster_tolerance);
    clustering.setMinClusterSize(options.min_inliers);
    clustering.setSearchMethod(tree);
    clustering.setInputCloud(plane_cloud);
    clustering.extract(clusters);
    for (const auto& cluster : clusters) {
      planes.push_back(observePlane(pointsOf(*plane_cloud, cluster.indices),
                                    int(cluster.indices.size()), options));
    }

    auto rest = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    extract.setNegative(true);
    extract.filter(*rest);
    remaining = rest;
  }
  return planes;
}

double dominantYaw(const std::vector<PlaneObservation>& planes) {
  constexpr int kBins = 90;
  std::array<double, kBins> histogram{};
  auto modulo90 = [](double yaw) {
    double a = std::fmod(yaw, std::numbers::pi / 2);
    return a < 0 ? a + std::numbers::pi / 2 : a;
  };
  for (const auto& p : planes) {
    if (p.orientation != PlaneOrientation::kVertical) continue;
    const double a = modulo90(std::atan2(p.plane.normal.y(), p.plane.normal.x()));
    histogram[std::min(kBins - 1, int(a / (std::numbers::pi / 2) * kBins))] += p.points;
  }
  // The peak of the histogram smoothed over ±2° (circularly: 0° and 89° are neighbours).
  int best = 0;
  double best_weight = -1;
  for (int b = 0; b < kBins; ++b) {
    double w = 0;
    for (int k = -2; k <= 2; ++k) w += histogram[(b + k + kBins) % kBins];
    if (w > best_weight) {
      best_weight = w;
      best = b;
    }
  }
  // Refine: the weighted circular mean (period 90°) of the planes within 5° of the peak.
  const double peak = (best + 0.5) * (std::numbers::pi / 2) / kBins;
  double s = 0, c = 0;
  for (const auto& p : planes) {
    if (p.orientation != PlaneOrientation::kVertical) continue;
    const double a = modulo90(std::atan2(p.plane.normal.y(), p.plane.normal.x()));
    const double d = common::remainderOf(a - peak, std::numbers::pi / 2);
    if (std::abs(d) > 5.0 * std::numbers::pi / 180.0) continue;
    s += p.points * std::sin(4 * a);
    c += p.points * std::cos(4 * a);
  }
  if (s == 0 && c == 0) return peak;
  return modulo90(std::atan2(s, c) / 4);
}

WallAxis classifyWall(const PlaneObservation& plane, double dominant_yaw, double tolerance) {
  if (plane.orientation != PlaneOrientation::kVertical) return WallAxis::kOther;
  const double yaw = std::atan2(plane.plane.normal.y(), plane.plane.normal.x());
  const double d = std::abs(
      common::remainderOf(yaw - dominant_yaw, std::numbers::pi));  // either sense: [0, π/2]
  if (d < tolerance) return WallAxis::kX;
  if (std::abs(d - std::numbers::pi / 2) < tolerance) return WallAxis::kY;
  return WallAxis::kOther;
}

}  // namespace isg::slam
