#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "run/driver.hpp"
#include "run/evaluate_run.hpp"
#include "run/foxglove/run_mcap.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// A run's MCAP file (RunMcapWriter) written as the run goes: observe() is runLocalizer's
// observer; each new estimate is a moment, at each snapshot the localizer's graph is kept, and
// the first scan the localizer reads from each snapshot on. finish() adds the final graph and the
// deviations and closes the file.
//
// The loop only gathers (the estimate, the graph, a copy of the scan); drawing, serialising,
// compressing and writing happen on a thread of the writer's own, at most kMaxQueued moments
// behind, so that the loop does not wait for the file. An error on that thread (a full disk)
// comes back on the loop's at its next call.
class LiveRunMcap {
 public:
  LiveRunMcap(const std::string& path, const RunMcapOptions& options, const RunSetup& setup,
              const sensors::SensorStreams& streams);
  // Without finish() (the run failed): the thread stops and no file is left.
  ~LiveRunMcap();
  LiveRunMcap(const LiveRunMcap&) = delete;
  LiveRunMcap& operator=(const LiveRunMcap&) = delete;

  void observe(const sensors::Scan* scan, const slam::Localizer& localizer,
               const LocalizerDriver& driver);
  void finish(const RunRecord& record, const RunEvaluation& evaluation);
  // An observer calling observe() on this.
  RunObserver observer();

  // After finish().
  const RunMcapWriter& writer() const { return writer_; }

  static constexpr std::size_t kMaxQueued = 64;

 private:
  void post(std::function<void()> task);
  void work();
  void stop();
  void rethrow();

  std::optional<nlohmann::json> agraph_;  // agraph.json's document, when the run has a plan
  RunMcapWriter writer_;
  double snapshot_period_;
  std::optional<double> last_snapshot_;
  std::size_t rows_seen_ = 0, estimate_rows_seen_ = 0, events_seen_ = 0;
  bool scan_wanted_ = true;  // a snapshot was taken since the last scan kept

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once everything it uses is built
};

}  // namespace isg::run
