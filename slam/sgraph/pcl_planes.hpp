#pragma once

// Private to slam/ (its sources and tests): the PCL steps behind slam::extractPlanes. No header
// outside slam/ may include this one, so that no user of slam compiles PCL (docs/architecture.md).
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "slam/sgraph/plane_extraction.hpp"

namespace isg::slam {

// Range crop and voxel grid of a scan, as a PCL cloud in the scan's frame.
pcl::PointCloud<pcl::PointXYZ>::Ptr preprocess(const sensors::Scan& scan,
                                               const PlaneExtractionOptions& options);

// Sequential RANSAC on a preprocessed cloud (see extractPlanes(Scan)).
std::vector<PlaneObservation> extractPlanes(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                            const PlaneExtractionOptions& options);

}  // namespace isg::slam
