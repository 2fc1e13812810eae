#pragma once

#include <string>
#include <vector>

#include "common/tum.hpp"

namespace isg::formats {

// A TUM trajectory file read for a command: any problem (no file, a bad line, poses out of time
// order, no pose at all when `require_poses`) is a common::InputError naming the file and the line,
// so the command exits 1 with it.
common::Trajectory readTrajectoryFile(const std::string& path, bool require_poses = true);

// scans.txt: one time a line (seconds), increasing; blank and '#' lines skipped. Problems are
// InputErrors naming the file and the line.
std::vector<double> readStampsFile(const std::string& path);

}  // namespace isg::formats
