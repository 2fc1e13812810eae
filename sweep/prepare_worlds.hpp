#pragma once

#include <string>
#include <vector>

#include "sweep/suite.hpp"

namespace isg::sweep {

// Reads every world of the suite as isg run will (a bad file fails here, not in each of its
// cells) and sets its content hash (worlds::worldHash). Generated worlds are written into
// SWEEP_DIR/worlds/ — rewritten when the file there is not what the spec makes now — and must be
// toured whole: a building whose tour cannot reach a room is an InputError naming the suite and
// the room, never a table number.
void prepareSweepWorlds(Suite& suite, const std::string& sweep_dir);

// The worlds whose hash differs from the one a sweep folder's sweep.json recorded (worlds it
// did not record are not listed: a sweep.json from before hashes; their cells are checked one by
// one).
struct ChangedWorld {
  std::string name, before, now;
};
std::vector<ChangedWorld> changedWorlds(const Suite& suite, const SweepPlan& before);

}  // namespace isg::sweep
