#include "run/foxglove/live_run_mcap.hpp"

#include <utility>

#include "bim/agraph_json.hpp"
#include "slam/match_status.hpp"

namespace isg::run {

namespace {

std::optional<nlohmann::json> agraphDocument(const RunSetup& setup) {
  if (!setup.agraph) return std::nullopt;
  return nlohmann::json::parse(bim::agraphJsonText(bim::agraphToJson(*setup.agraph)));
}

}  // namespace

LiveRunMcap::LiveRunMcap(const std::string& path, const RunMcapOptions& options,
                         const RunSetup& setup, const sensors::SensorStreams& streams)
    : agraph_(agraphDocument(setup)),
      writer_(path, options, agraph_ ? &*agraph_ : nullptr, streams.R_T_L, streams.ground_truth),
      snapshot_period_(options.snapshot_period),
      thread_([this] { work(); }) {}

LiveRunMcap::~LiveRunMcap() {
  {
    // After finish() there is nothing left; without it, the run failed: nothing more is written.
    std::lock_guard lock(mutex_);
    tasks_.clear();
  }
  stop();
}

void LiveRunMcap::post(std::function<void()> task) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return tasks_.size() < kMaxQueued || error_; });
  if (error_) return;  // rethrown by the caller
  tasks_.push_back(std::move(task));
  changed_.notify_all();
}

void LiveRunMcap::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !tasks_.empty() || stopping_; });
      if (tasks_.empty() || error_) return;  // stopping, and all done (or failed)
      task = std::move(tasks_.front());
      tasks_.pop_front();
      changed_.notify_all();
    }
    try {
      task();
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      tasks_.clear();
      changed_.notify_all();
      return;
    }
  }
}

void LiveRunMcap::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
}

void LiveRunMcap::rethrow() {
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void LiveRunMcap::observe(const sensors::Scan* scan, const slam::Localizer& localizer,
                          const LocalizerDriver& driver) {
  rethrow();
  if (scan && scan_wanted_) {
    post([this, kept = *scan] { writer_.addScan(kept); });
    scan_wanted_ = false;
  }
  const Trajectory& rows = driver.estimateMap();
  if (rows.size() == rows_seen_) return;  // no new estimate: nothing has moved
  rows_seen_ = rows.size();
  RunMoment moment;
  moment.stamp = rows.back().t;
  moment.M_T_R = rows.back().pose;
  if (driver.estimate().size() > estimate_rows_seen_) {
    estimate_rows_seen_ = driver.estimate().size();
    moment.B_T_M = driver.mapInPlan();
  }
  const std::vector<slam::StatusChange> changes = localizer.statusChanges();
  for (; events_seen_ < changes.size(); ++events_seen_) {
    const slam::StatusChange& change = changes[events_seen_];
    moment.events.push_back(
        {change.stamp, change.keyframe, slam::toString(change.status), change.reason});
  }
  std::optional<nlohmann::json> graph;
  if (snapshotDue(last_snapshot_, moment.stamp, snapshot_period_)) {
    last_snapshot_ = moment.stamp;
    graph = localizer.graph();  // the localizer is the loop's: read here, drawn there
    scan_wanted_ = true;
  }
  post([this, moment = std::move(moment), graph = std::move(graph)]() mutable {
    if (graph) moment.graph = &*graph;
    writer_.add(moment);
  });
}

void LiveRunMcap::finish(const RunRecord& record, const RunEvaluation& evaluation) {
  // The last task: the thread is joined before `record` and `evaluation` go.
  post([&] {
    writer_.finish(record.graph, evaluation.deviations ? &*evaluation.deviations : nullptr);
  });
  stop();
  rethrow();
}

RunObserver LiveRunMcap::observer() {
  return [this](const sensors::Scan* scan, const slam::Localizer& localizer,
                const LocalizerDriver& driver) { observe(scan, localizer, driver); };
}

}  // namespace isg::run
