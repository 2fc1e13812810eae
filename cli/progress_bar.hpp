#pragma once

#include <chrono>
#include <string>

namespace isg::cli {

// A one-line progress bar on stderr, redrawn at most ten times a second; silent when stderr is
// not a terminal or when quiet, so that logs and CI output stay clean.
class ProgressBar {
 public:
  ProgressBar(std::string label, bool quiet);
  ~ProgressBar();
  void update(double fraction, const std::string& detail);
  void finish();

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace isg::cli
