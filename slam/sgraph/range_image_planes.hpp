#pragma once

#include <optional>
#include <vector>

#include "slam/sgraph/plane_extraction.hpp"

namespace isg::slam {

// Planes of an organised scan on its range image (docs/slam.md, "Plane extraction"): rows are the
// rings, columns azimuth bins of `image_column_deg`; each cell's normal from its neighbours in the
// image; regions grown from cell to neighbouring cell while the cells stay close, on the region's
// plane and turned alike; adjacent regions on one plane merged; each region fitted by least
// squares to its points. Linear in the points, where RANSAC on an unorganised cloud is not.
// nullopt when the scan is not organised (its points name fewer than 4 rings): then RANSAC.
std::optional<std::vector<PlaneObservation>> extractPlanesOnRangeImage(
    const sensors::Scan& scan, const PlaneExtractionOptions& options);

}  // namespace isg::slam
