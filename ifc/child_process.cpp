#include "ifc/child_process.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/input_error.hpp"
#include "ifc/ifc_importer.hpp"

namespace isg::ifc {
namespace {

// The steps that run IFC++: the model read, the elements fitted, the plan's JSON made (no parse).
ImportResult importWithIfcpp(const std::string& file, std::string text,
                             const ImportOptions& options) {
  LoadedModel loaded = loadModel(file, std::move(text));
  importer::Importer importer(file, loaded, options);
  ImportResult result = importer.run();
  result.reader_errors = loaded.messages.errors;
  return result;
}

// What crosses from the child process to the parent.
nlohmann::json resultToMessage(const ImportResult& r) {
  nlohmann::json storeys = nlohmann::json::array();
  for (const auto& s : r.storeys) {
    storeys.push_back({{"name", s.name},
                       {"global_id", s.global_id},
                       {"elevation", s.elevation},
                       {"level_id", s.level_id},
                       {"why_not", s.why_not},
                       {"counts",
                        {s.walls, s.walls_from_other_storeys, s.doors, s.windows, s.rooms, s.spaces,
                         s.columns}}});
  }
  return {{"ok", true},
          {"plan", r.plan_json.dump()},
          {"schema", r.schema},
          {"application", r.application},
          {"metres_per_unit", r.metres_per_unit},
          {"log", r.log},
          {"storeys", storeys},
          {"reader_errors", r.reader_errors}};
}

ImportResult resultFromMessage(const nlohmann::json& m) {
  ImportResult r;
  r.plan_json = nlohmann::ordered_json::parse(m.at("plan").get<std::string>());
  r.schema = m.at("schema").get<std::string>();
  r.application = m.at("application").get<std::string>();
  r.metres_per_unit = m.at("metres_per_unit").get<double>();
  r.log = m.at("log").get<std::vector<std::string>>();
  r.reader_errors = m.at("reader_errors").get<std::vector<std::string>>();
  for (const auto& s : m.at("storeys")) {
    StoreySummary summary;
    summary.name = s.at("name").get<std::string>();
    summary.global_id = s.at("global_id").get<std::string>();
    summary.elevation = s.at("elevation").get<double>();
    summary.level_id = s.at("level_id").get<std::string>();
    summary.why_not = s.at("why_not").get<std::string>();
    const auto& c = s.at("counts");
    summary.walls = c.at(0), summary.walls_from_other_storeys = c.at(1), summary.doors = c.at(2);
    summary.windows = c.at(3), summary.rooms = c.at(4), summary.spaces = c.at(5);
    summary.columns = c.at(6);
    r.storeys.push_back(summary);
  }
  return r;
}

void writeAll(int fd, const std::string& bytes) {
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

std::string readAll(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

// IFC++ is not robust against malformed models (ci/fuzz found null dereferences in its geometry
// code, and leaks): it runs in a child process, so that whatever it does to a bad file, isg
// reports the file and exits 1 with nothing written.
ImportResult importInChildProcess(const std::string& file, std::string text,
                                  const ImportOptions& options) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot make a pipe for the IFC reader");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    throw std::runtime_error("cannot start the IFC reader's process");
  }
  if (pid == 0) {
    ::close(fds[0]);
    // The child dies of what kills it, whatever handlers the parent installed (isg's interrupt
    // flag, a sanitizer's or libFuzzer's crash reports): the parent reads its signal, a Ctrl-C
    // stops it at once, and a crash inside IFC++ is the parent's to report.
    for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGINT, SIGTERM, SIGHUP}) {
      std::signal(signal, SIG_DFL);
    }
    nlohmann::json message;
    try {
      message = resultToMessage(importWithIfcpp(file, std::move(text), options));
    } catch (const common::InputError& e) {
      message = {{"ok", false}, {"pointer", e.pointer()}, {"reason", e.reason()}};
    } catch (const std::exception& e) {
      message = {{"ok", false}, {"internal", e.what()}};
    }
    writeAll(fds[1], message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    ::close(fds[1]);
    ::_exit(0);  // neither the parent's exit handlers nor its buffers
  }
  ::close(fds[1]);
  const std::string bytes = readAll(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGINT || signal == SIGTERM || signal == SIGHUP) throw ImportInterrupted(signal);
    throw common::InputError(file, "",
                             "IFC++ stopped with signal " + std::to_string(signal) + " (" +
                                 strsignal(signal) +
                                 ") while reading the model: it is malformed, or uses what IFC++ "
                                 "(Debian's libifcplusplus) cannot read");
  }
  const nlohmann::json message = nlohmann::json::parse(bytes, nullptr, false);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || message.is_discarded() ||
      !message.is_object()) {
    throw common::InputError(file, "",
                             "IFC++ stopped while reading the model (exit status " +
                                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                                 "): it is malformed, or uses what IFC++ cannot read");
  }
  if (!message.value("ok", false)) {
    if (message.contains("internal")) {
      throw std::runtime_error("the IFC import: " + message["internal"].get<std::string>());
    }
    throw common::InputError(file, message.value("pointer", ""), message.value("reason", ""));
  }
  return resultFromMessage(message);
}

}  // namespace isg::ifc
