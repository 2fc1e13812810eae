#pragma once

#include "sensors/messages.hpp"
#include "sensors/stage_times.hpp"

namespace isg::sensors {

// Where a run's scans come from: the simulator casting them (sim/), or a recorded dataset
// (DatasetReader). For each k = 0, 1, … in order, either `scan(k)` or `skip(k)` is called once:
// skip when the localizer will not read scan k, so that it need not be made or read at all. The
// scan's stamp is the stream's, so a source only fills the points.
class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual Scan scan(int index) = 0;
  virtual void skip(int /*index*/) {}
  // Seconds the source spent by stage (the simulator's poses, casting, noise; a dataset's
  // reading), for the run's stage timing.
  virtual StageTimes stageTimes() const { return {}; }
};

}  // namespace isg::sensors
