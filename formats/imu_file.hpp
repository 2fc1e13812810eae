#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::formats {

// A dataset's imu.csv (docs/formats.md): the header line "t,ax,ay,az,gx,gy,gz", then one sample
// per line. Any problem (no file, a wrong header, a line that is not 7 finite numbers, times that
// do not increase) is a common::InputError naming the file and the line.
std::vector<sensors::ImuSample> readImuFile(const std::string& path);
// The same for text already in memory; errors name `file`.
std::vector<sensors::ImuSample> parseImuText(std::string_view text, const std::string& file);

}  // namespace isg::formats
