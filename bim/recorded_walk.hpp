#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {

// A recorded walk is read as a TUM file (docs/simulation.md, "Replayed walks"): its poses in the
// plan frame of the robot's level (z above the level's floor, and roll and pitch, used for a
// sensor's path only), its stamps made relative to the first. It is refused (InputError naming
// the file and the line) when it cannot be read, holds fewer than two poses, is longer than
// limits::kMaxRobotSeconds, or moves faster than kMaxCarriedSpeed; a single pose off the walk
// (too fast to reach and to leave, its neighbours agreeing: a tracking glitch) is left out and
// said, a gap in time beyond kWalkGapWarning is said — both as warnings on `node` (the
// scenario's "trajectory" field) —, as is a pose far outside the level's walls.
//
// The limit is a sensor's, not a walker's: a recorded path is a sensor's (a camera held off the
// walker's axis swings through 2.5–3 m/s for a second where the walker turns), and a carrier
// replaying it as a body's smooths the swing away (sim/walk_path.hpp). Beyond 6 m/s over any
// 0.05 s or more nobody carries a sensor: a relocalization's jump, or a pose in another frame.
inline constexpr double kMaxCarriedSpeed = 6.0;    // m/s
inline constexpr double kWalkGapWarning = 1.0;     // s without a pose
inline constexpr double kWalkOutsideWarning = 20;  // m beyond the box of the level's walls
// The walk's file, before it is read: each pose costs about 600 bytes while a run holds it (the
// text, the pose, the route and the truth made of it), so 64 MiB — some 750 000 poses, two hours
// at 100 Hz — is at most about half a GiB.
inline constexpr std::uintmax_t kMaxWalkFileBytes = 64ull << 20;

// `walk` of the result holds its poses, `recording_start` the file's first stamp (the walk's t = 0
// in its own clock), `bridged` the times of the glitches left out; `file` is left to the caller.
LoadedWalk readRecordedWalk(const std::string& path, const Level& level,
                            const common::JsonNode& node);

}  // namespace isg::bim
