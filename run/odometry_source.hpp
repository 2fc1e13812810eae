#pragma once

#include <memory>

#include "sensors/sensor_streams.hpp"
#include "slam/localizer.hpp"

namespace isg::run {

// A localizer as a run with these streams feeds it: unchanged when the streams have odometry;
// otherwise (a handheld sensor, a recording without wheel or leg odometry) behind a
// ScanOdometryLocalizer that makes its odometry from the LiDAR and, when the streams have one,
// the IMU (docs/slam.md, "Without odometry").
std::unique_ptr<slam::Localizer> withOdometrySource(std::unique_ptr<slam::Localizer> localizer,
                                                    const sensors::SensorStreams& streams);

}  // namespace isg::run
