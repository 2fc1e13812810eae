#include "sensors/trajectory_file.hpp"

#include "bim/input_error.hpp"

namespace isg::sensors {

eval::Trajectory readTrajectoryFile(const std::string& path, bool require_poses) {
  eval::Trajectory trajectory;
  try {
    trajectory = eval::readTum(path);
  } catch (const eval::TumError& e) {
    throw bim::InputError(path, "", e.located());
  }
  if (require_poses && trajectory.empty()) {
    throw bim::InputError(path, "", "no poses (a TUM file holds one pose per line)");
  }
  return trajectory;
}

}  // namespace isg::sensors
