#pragma once

#include <chrono>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace isg::sensors {

// Seconds spent in the named stages of a run (deskew, extraction, casting, ...), in the order the
// stages were first reported; what `isg run --timing` and metrics.json's `timing` show. A handful
// of stages, added to once per keyframe or scan: a list is all it needs.
class StageTimes {
 public:
  void add(std::string_view stage, double seconds) {
    for (auto& [name, total] : stages_) {
      if (name == stage) {
        total += seconds;
        return;
      }
    }
    stages_.emplace_back(std::string(stage), seconds);
  }
  void add(const StageTimes& other) {
    for (const auto& [name, seconds] : other.stages_) add(name, seconds);
  }
  double seconds(std::string_view stage) const {
    for (const auto& [name, total] : stages_) {
      if (name == stage) return total;
    }
    return 0.0;
  }
  double total() const {
    double sum = 0.0;
    for (const auto& stage : stages_) sum += stage.second;
    return sum;
  }
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }

 private:
  std::vector<std::pair<std::string, double>> stages_;
};

// Adds the time from its construction to its destruction (or to stop()) to one stage.
class StageClock {
 public:
  StageClock(StageTimes& times, std::string_view stage)
      : times_(&times), stage_(stage), start_(std::chrono::steady_clock::now()) {}
  ~StageClock() { stop(); }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

  // Adds the time so far to the stage (once) and returns it, for a caller that also keeps it.
  double stop() {
    if (!times_) return 0.0;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    times_->add(stage_, seconds);
    times_ = nullptr;
    return seconds;
  }

 private:
  StageTimes* times_;
  std::string_view stage_;  // a literal's view: stage names are string literals
  std::chrono::steady_clock::time_point start_;
};

}  // namespace isg::sensors
