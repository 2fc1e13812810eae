#pragma once

#include <string>

#include "eval/tum.hpp"

namespace isg::sensors {

// A TUM trajectory file read for a command: any problem (no file, a bad line, poses out of time
// order, no pose at all when `require_poses`) is a bim::InputError naming the file and the line,
// so the command exits 1 with it.
eval::Trajectory readTrajectoryFile(const std::string& path, bool require_poses = true);

}  // namespace isg::sensors
