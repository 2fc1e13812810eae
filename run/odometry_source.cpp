#include "run/odometry_source.hpp"

#include "slam/sgraph/scan_odometry_localizer.hpp"

namespace isg::run {

std::unique_ptr<slam::Localizer> withOdometrySource(std::unique_ptr<slam::Localizer> localizer,
                                                    const sensors::SensorStreams& streams) {
  if (!streams.odometry.empty()) return localizer;
  return std::make_unique<slam::ScanOdometryLocalizer>(std::move(localizer), streams.R_T_L,
                                                       streams.R_T_I);
}

}  // namespace isg::run
