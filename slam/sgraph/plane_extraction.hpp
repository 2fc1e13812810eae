#pragma once

#include <Eigen/Core>
#include <numbers>
#include <utility>
#include <vector>

#include "bim/plane.hpp"
#include "sensors/messages.hpp"

namespace isg::slam {

// Planes from one (deskewed) scan: docs/slam.md. Defaults are the documented starting values.
struct PlaneExtractionOptions {
  enum class Method {
    kRangeImage,  // organised scans (points with rings) on the range image; RANSAC otherwise
    kRansac,      // always sequential RANSAC on the voxel-filtered cloud
  };
  Method method = Method::kRangeImage;
  double min_range = 0.5;  // metres: closer points are the robot or noise
  double max_range = 30.0;
  double voxel = 0.1;  // voxel leaf: RANSAC's grid; the range image counts support in voxels
  double ransac_distance = 0.04;  // a point's distance from its plane, both methods
  int min_inliers = 100;          // support: points after the voxel grid, voxels on the range image
  // Horizontal surfaces on the range image need less: a sensor held high (a handheld rig at 1.5 m)
  // sees the floor only where the lowest rings meet it, 5 m off or more, in an arc or two; only
  // the floor's height is taken from them (SGraph), robustly. Other planes keep min_inliers.
  int horizontal_min_inliers = 30;
  int max_planes = 30;
  // A plane's points are split where they are this far apart, so that two coplanar walls (a
  // corridor's two sides of a doorway, the same wall in two rooms) are separate.
  double cluster_tolerance = 0.3;
  // Range image: azimuth bin; a region's cells turn within normal_angle_deg of its plane;
  // adjacent regions within merge_angle_deg (and the plane distance) are one; neighbours across
  // rings are close up to ring_gap_factor × the rings' spacing at their range.
  double image_column_deg = 0.8;
  double normal_angle_deg = 15.0;
  double merge_angle_deg = 5.0;
  double ring_gap_factor = 4.0;
  // A wall's inliers leave a hole (a gap in a wall built in part, seen through) where, along the
  // wall, none lies over more than cluster_tolerance and over more than hole_columns azimuth bins
  // of image_column_deg at that range and angle: the sampling alone leaves gaps that wide on a
  // wall seen far off at a grazing angle.
  double hole_columns = 2.0;
  // Where along a wall its inliers stand: in each wall_column_width along it, over at least
  // wall_column_height. A ring's arc across the floor or the ceiling, tangent to the wall's line
  // where nothing stands (a gap in a wall built in part), lies in the wall's plane at one height.
  double wall_column_width = 0.05;
  double wall_column_height = 0.15;
  double vertical_max_normal_z = 0.2;    // |n_z| below this: a wall
  double horizontal_min_normal_z = 0.9;  // above this: a floor or a ceiling
};

enum class PlaneOrientation { kVertical, kHorizontal, kOblique };

// What the scan says about a wall's top: whether the rays just above its highest points went
// past it (kSeen: z_max is where the surface ends), or its top was beyond what the sensor could
// see of it (kBeyondView: the rings above it ran out, or met something nearer such as the
// ceiling). Unorganised scans cannot tell (kUnknown).
enum class TopEdge { kUnknown, kBeyondView, kSeen };

struct PlaneObservation {
  bim::Plane plane;  // in the scan's frame, normal towards the frame's origin (the sensor)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int points = 0;
  PlaneOrientation orientation = PlaneOrientation::kOblique;
  // Walls: the inliers' extent along the wall (the horizontal direction in the plane) and in z.
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();
  // Walls: the parts of start → end its inliers stand on, as shares (0 at start, 1 at end), apart
  // where they leave a hole (PlaneExtractionOptions::hole_columns, wall_column_height); empty
  // when all of it. Only what the map confirms of a wall reads them (SGraph::Plane::spans).
  std::vector<std::pair<double, double>> pieces;
  double z_min = 0.0, z_max = 0.0;
  double rms = 0.0;  // inliers' RMS distance from the plane
  TopEdge top = TopEdge::kUnknown;
};

// The planes of a scan, in the scan's frame, largest support first. Organised scans (Method
// kRangeImage): region growing on the range image (slam/sgraph/range_image_planes.hpp). Otherwise
// range crop and voxel grid, then sequential RANSAC (PCL SACMODEL_PLANE) removing each plane's
// inliers, each plane's inliers split by Euclidean clustering, planes fitted again by least
// squares to each cluster. PCL stays behind this call (slam/sgraph/pcl_planes.hpp is slam's own):
// no user of slam compiles PCL.
std::vector<PlaneObservation> extractPlanes(const sensors::Scan& scan,
                                            const PlaneExtractionOptions& options);

// The building's dominant yaw in [0, π/2), from the vertical planes' normals (a histogram of
// their yaw modulo 90°, weighted by points, refined by the mean of the peak's neighbourhood), so
// that x/y classification works whatever the robot's start heading.
double dominantYaw(const std::vector<PlaneObservation>& planes);

enum class WallAxis { kX, kY, kOther };
// x: normal within `tolerance` of the dominant direction (either sense); y: of its perpendicular.
WallAxis classifyWall(const PlaneObservation& plane, double dominant_yaw,
                      double tolerance_rad = 20.0 * std::numbers::pi / 180.0);

}  // namespace isg::slam
