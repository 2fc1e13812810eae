#pragma once

// Private to slam/: the least-squares plane both extractors (range image, RANSAC) end with.
#include <Eigen/Core>
#include <vector>

#include "slam/sgraph/plane_extraction.hpp"

namespace isg::slam {

// The least-squares plane of `points` (in the scan's frame) as an observation: normal towards the
// frame's origin (the sensor), orientation by the normal's z, extent along the wall and in z, RMS
// distance. `support`: the observation's `points` (the extractors count 10 cm voxels).
PlaneObservation observePlane(const std::vector<Eigen::Vector3d>& points, int support,
                              const PlaneExtractionOptions& options);

}  // namespace isg::slam
