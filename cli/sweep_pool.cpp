#include "cli/sweep_pool.hpp"

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

#include "cli/interrupt.hpp"
#include "run/atomic_folder.hpp"

namespace isg::cli {

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
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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

bool cellFinished(const std::string& sweep_dir, const SweepCell& cell) {
  return fs::exists(fs::path(sweep_dir) / cell.dir / "metrics.json");
}

PoolOutcome runCells(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                     const std::vector<std::size_t>& indices, int jobs, bool quiet) {
  // This very executable, even if a rebuild has replaced its file since the sweep started.
  const std::string isg = "/proc/self/exe";
  const fs::path dir = fs::absolute(sweep_dir);
  PoolOutcome outcome;
  std::vector<std::size_t> pending;
  for (std::size_t i : indices) {
    if (cellFinished(sweep_dir, cells[i])) {
      ++outcome.skipped;
    } else {
      pending.push_back(i);
    }
  }
  const std::size_t total = indices.size();
  if (!quiet && outcome.skipped > 0) {
    std::fprintf(stderr, "isg sweep: %d of %zu cells finished before; running the other %zu\n",
                 outcome.skipped, total, pending.size());
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
      throwIfInterrupted();
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
      const fs::path log = dir / "logs" / (cell.dir + ".log");
      const bool ok =
          WIFEXITED(status) && WEXITSTATUS(status) == 0 && cellFinished(sweep_dir, cell);
      std::string what;
      if (ok) {
        ++outcome.finished;
        seconds_run += seconds;
        fs::remove(failureRecordPath(sweep_dir, cell));
        what = "done in " + duration(seconds);
      } else {
        ++outcome.failed;
        const auto lines = lastLines(log, 20);
        nlohmann::json record = {{"world", cell.world},
                                 {"method", cell.method},
                                 {"seed", cell.seed},
                                 {"command", quoted(cell.arguments)},
                                 {"log", "logs/" + cell.dir + ".log"},
                                 {"seconds", std::round(seconds * 10) / 10},
                                 {"error", lines}};
        if (WIFEXITED(status)) record["exit_code"] = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) record["signal"] = WTERMSIG(status);
        run::writeFileAtomically(failureRecordPath(sweep_dir, cell), record.dump(1) + "\n");
        std::string reason = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                               : "signal " + std::to_string(WTERMSIG(status));
        what = "FAILED (" + reason + ")" + (lines.empty() ? "" : ": " + lines.back());
      }
      report = cell.dir + " " + what;
    }
    printReport();
  } catch (...) {
    stopChildren();
    throw;
  }
  return outcome;
}

}  // namespace isg::cli
