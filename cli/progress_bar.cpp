#include "cli/progress_bar.hpp"

#include "run/interrupt.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace isg::cli {

ProgressBar::ProgressBar(std::string label, bool quiet)
    : label_(std::move(label)), enabled_(!quiet && ::isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double fraction, const std::string& detail) {
  // Every long command reports here once per scan, drawn or quiet: the place to notice Ctrl-C.
  run::throwIfInterrupted();
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  constexpr int kWidth = 30;
  const int filled = std::clamp(int(fraction * kWidth + 0.5), 0, kWidth);
  std::fprintf(stderr, "\r%s [%s%s] %3d%% %s\033[K", label_.c_str(),
               std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(),
               int(fraction * 100 + 0.5), detail.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace isg::cli
