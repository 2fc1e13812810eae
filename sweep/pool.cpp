#include "sweep/pool.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/plural.hpp"
#include "run/builtin_methods.hpp"
#include "run/interrupt.hpp"
#include "run/run_metrics.hpp"

namespace isg::sweep {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Running {
  std::size_t index;
  Clock::time_point start;
};

// Starts `isg ARGUMENTS` in `dir` with its output in `log`; the child dies with its parent.
pid_t startChild(const std::string& isg, const std::vector<std::string>& arguments,
                 const fs::path& dir, const fs::path& log) {
  std::vector<std::string> argv_storage = {"isg"};
  argv_storage.insert(argv_storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    // Only async-signal-safe calls from here on.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(128 + SIGTERM);  // the parent died before prctl
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    if (chdir(dir.c_str()) != 0) _exit(126);
    // O_NOFOLLOW: a log replaced by a symlink never truncates the file it points to.
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    const int in = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (out < 0 || in < 0) _exit(126);
    dup2(in, 0);
    dup2(out, 1);
    dup2(out, 2);
    execv(isg.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// The last non-empty lines of a log, for the failure record and the progress line.
std::vector<std::string> lastLines(const fs::path& log, std::size_t count) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) lines.push_back(line);
  }
  if (lines.size() > count) lines.erase(lines.begin(), lines.end() - long(count));
  return lines;
}

std::string quoted(const std::vector<std::string>& arguments) {
  std::string out = "isg";
  for (const auto& a : arguments) {
    const bool plain = a.find_first_of(" '\"\\$") == std::string::npos && !a.empty();
    out += " " + (plain ? a : "'" + a + "'");
  }
  return out;
}

std::string duration(double seconds) {
  char b[32];
  if (seconds < 10) {
    std::snprintf(b, sizeof b, "%.1f s", seconds);
  } else if (seconds < 90) {
    std::snprintf(b, sizeof b, "%.0f s", seconds);
  } else if (seconds < 5400) {
    std::snprintf(b, sizeof b, "%.0f min", seconds / 60);
  } else {
    std::snprintf(b, sizeof b, "%.1f h", seconds / 3600);
  }
  return b;
}

}  // namespace

std::string failureRecordPath(const std::string& sweep_dir, const SweepCell& cell) {
  return (fs::path(sweep_dir) / (cell.dir + ".failed.json")).string();
}

CellCheck checkCell(const std::string& sweep_dir, const SweepCell& cell) {
  using State = CellCheck::State;
  const fs::path dir = fs::path(sweep_dir) / cell.dir;
  std::error_code error;
  const fs::file_status status = fs::symlink_status(dir, error);
  if (!fs::exists(status)) return {State::kMissing, ""};
  if (!fs::is_directory(status)) return {State::kDamaged, "not a folder"};
  run::RunMetrics metrics;
  try {
    metrics = run::readMetrics(dir.string());
  } catch (const std::exception& e) {
    return {State::kDamaged, e.what()};
  }
  if (metrics.seed != cell.seed) {
    return {State::kDamaged, "its metrics.json is of seed " + std::to_string(metrics.seed)};
  }
  if (run::builtinMethods().canonical(metrics.method) != cell.method) {
    return {State::kDamaged, "its metrics.json is of method " + metrics.method};
  }
  if (!cell.world_hash.empty() && metrics.world_hash != cell.world_hash) {
    return {State::kDamaged, metrics.world_hash
                                 ? "it ran on another world (" + *metrics.world_hash + ", not " +
                                       cell.world_hash + ")"
                                 : "its metrics.json names no world hash: not a run of this sweep "
                                   "(or of an isg before world hashes)"};
  }
  return {State::kFinished, ""};
}

bool cellFinished(const std::string& sweep_dir, const SweepCell& cell) {
  return checkCell(sweep_dir, cell).state == CellCheck::State::kFinished;
}

std::string moveCellAside(const std::string& sweep_dir, const SweepCell& cell) {
  const fs::path base = fs::path(kSweepAsideFolder) / cell.dir;
  fs::path relative = base;
  for (int k = 2; fs::exists(fs::symlink_status(fs::path(sweep_dir) / relative)); ++k) {
    relative = base.string() + "." + std::to_string(k);
  }
  const fs::path to = fs::path(sweep_dir) / relative;
  std::error_code error;
  fs::create_directories(to.parent_path(), error);
  if (!error) fs::rename(fs::path(sweep_dir) / cell.dir, to, error);
  if (error) {
    throw common::InputError((fs::path(sweep_dir) / cell.dir).string(), "",
                             "cannot move it aside to " + to.string() + ": " + error.message());
  }
  return relative.string();
}

namespace {

// The cells still to run: finished ones skipped (their stale failure records removed), damaged
// ones moved aside and run again.
std::vector<std::size_t> pendingCells(const std::string& sweep_dir,
                                      const std::vector<SweepCell>& cells,
                                      const std::vector<std::size_t>& indices,
                                      PoolOutcome& outcome) {
  std::vector<std::size_t> pending;
  for (std::size_t i : indices) {
    const CellCheck check = checkCell(sweep_dir, cells[i]);
    std::error_code ignored;
    if (check.state == CellCheck::State::kFinished) {
      ++outcome.skipped;
      // A failure record of an earlier attempt no longer says anything true.
      fs::remove(failureRecordPath(sweep_dir, cells[i]), ignored);
      continue;
    }
    if (check.state == CellCheck::State::kDamaged) {
      const std::string aside = moveCellAside(sweep_dir, cells[i]);
      std::fprintf(stderr, "isg sweep: %s: %s; moved to %s, running it again\n",
                   cells[i].dir.c_str(), check.why.c_str(), aside.c_str());
    }
    pending.push_back(i);
  }
  return pending;
}

// A cell whose child ended with `status` after `seconds`: finished (its folder is this cell's),
// or failed with its record beside it. Returns the line that says which.
std::string cellEnded(const std::string& sweep_dir, const fs::path& dir, const SweepCell& cell,
                      int status, double seconds, PoolOutcome& outcome, double& seconds_run) {
  const fs::path log = dir / "logs" / (cell.dir + ".log");
  const CellCheck check = checkCell(sweep_dir, cell);
  const bool ok =
      WIFEXITED(status) && WEXITSTATUS(status) == 0 && check.state == CellCheck::State::kFinished;
  if (ok) {
    ++outcome.finished;
    seconds_run += seconds;
    std::error_code ignored;
    fs::remove(failureRecordPath(sweep_dir, cell), ignored);
    return "done in " + duration(seconds);
  }
  ++outcome.failed;
  auto lines = lastLines(log, 20);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    // The run ended well but its folder is not this cell's (its world changed meanwhile).
    lines.push_back("isg sweep: the run folder is not this cell's: " +
                    (check.why.empty() ? std::string("missing") : check.why));
  }
  nlohmann::json record = {{"world", cell.world},
                           {"method", cell.method},
                           {"seed", cell.seed},
                           {"command", quoted(cell.arguments)},
                           {"log", "logs/" + cell.dir + ".log"},
                           {"seconds", std::round(seconds * 10) / 10},
                           {"error", lines}};
  if (WIFEXITED(status)) record["exit_code"] = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) record["signal"] = WTERMSIG(status);
  common::writeFileAtomically(failureRecordPath(sweep_dir, cell), record.dump(1) + "\n");
  std::string reason = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                         : "signal " + std::to_string(WTERMSIG(status));
  return "FAILED (" + reason + ")" + (lines.empty() ? "" : ": " + lines.back());
}

}  // namespace

PoolOutcome runCells(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                     const std::vector<std::size_t>& indices, int jobs, bool quiet) {
  // This very executable, even if a rebuild has replaced its file since the sweep started.
  const std::string isg = "/proc/self/exe";
  const fs::path dir = fs::absolute(sweep_dir);
  PoolOutcome outcome;
  const std::vector<std::size_t> pending = pendingCells(sweep_dir, cells, indices, outcome);
  const std::size_t total = indices.size();
  if (!quiet && outcome.skipped > 0) {
    std::fprintf(stderr, "isg sweep: %d of %s finished before; running the other %zu\n",
                 outcome.skipped, common::counted(total, "cell").c_str(), pending.size());
  }
  std::map<pid_t, Running> running;
  double seconds_run = 0.0;
  std::size_t next = 0;
  const auto stopChildren = [&] {
    for (const auto& [pid, r] : running) kill(pid, SIGTERM);
    for (const auto& [pid, r] : running) waitpid(pid, nullptr, 0);
    running.clear();
  };
  // The line about the cell that ended last, printed once the free slot is filled again, so that
  // "running" counts what runs.
  std::string report;
  const auto printReport = [&] {
    if (quiet || report.empty()) return;
    const int done = outcome.finished + outcome.skipped;
    const std::size_t left = pending.size() - next + running.size();
    std::string eta;
    if (outcome.finished > 0 && left > 0) {
      const double mean = seconds_run / outcome.finished;
      eta = ", ETA " + duration(mean * std::ceil(double(left) / double(std::max(1, jobs))));
    }
    std::fprintf(stderr, "isg sweep: %d/%zu done, %zu running, %d failed%s — %s\n", done, total,
                 running.size(), outcome.failed, eta.c_str(), report.c_str());
    report.clear();
  };
  try {
    while (next < pending.size() || !running.empty()) {
      run::throwIfInterrupted();
      while (next < pending.size() && int(running.size()) < jobs) {
        const SweepCell& cell = cells[pending[next]];
        const fs::path log = dir / "logs" / (cell.dir + ".log");
        fs::create_directories(log.parent_path());
        fs::create_directories((dir / cell.dir).parent_path());
        running[startChild(isg, cell.arguments, dir, log)] = {pending[next], Clock::now()};
        ++next;
      }
      printReport();
      int status = 0;
      const pid_t pid = waitpid(-1, &status, WNOHANG);
      if (pid <= 0 || !running.count(pid)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      const Running r = running.at(pid);
      running.erase(pid);
      const SweepCell& cell = cells[r.index];
      const double seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
      report =
          cell.dir + " " + cellEnded(sweep_dir, dir, cell, status, seconds, outcome, seconds_run);
    }
    printReport();
  } catch (...) {
    stopChildren();
    throw;
  }
  return outcome;
}

}  // namespace isg::sweep
