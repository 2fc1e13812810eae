#include "sweep/slurm_backend.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"

namespace isg::sweep {

namespace {

namespace fs = std::filesystem;

// A word for bash: in single quotes, each single quote written '\''.
std::string shellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A value on an #SBATCH line. sbatch splits such a line at white space, takes backslash as an
// escape and an unquoted '#' as the start of a comment, so a value holding any of them (a sweep
// folder "runs #2", a suite named "nightly run") goes in double quotes, backslash-escaped.
std::string sbatchValue(const std::string& text) {
  if (text.find_first_of(" \t\"'\\#") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// A literal path in an --output pattern: '%' starts a replacement symbol there, "%%" is one '%'.
std::string slurmFilenamePattern(const std::string& path) {
  std::string out;
  for (char c : path) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

}  // namespace

std::string slurmScript(const std::string& sweep_dir, const Suite& suite, std::size_t tasks,
                        const std::string& isg, std::size_t max_array_size) {
  const std::string dir = fs::absolute(sweep_dir).lexically_normal().string();
  const std::size_t first_array = std::max<std::size_t>(1, std::min(tasks, max_array_size));
  std::string s = "#!/bin/bash\n";
  s += "# Written by isg sweep --backend slurm (docs/sweeps.md): one array task per cell left to\n";
  s +=
      "# run. Submitted as sbatch --array=0-N sweep.sbatch OFFSET (several arrays when the cells\n";
  s += "# are more than the cluster's MaxArraySize), task T runs the cell on line OFFSET+T+1 of\n";
  s += "# slurm-cells.txt. Submit again with isg sweep SUITE -o SWEEP_DIR --backend slurm:\n";
  s += "# finished cells are left out.\n";
  s += "#SBATCH --job-name=" + sbatchValue("isg-" + suite.name) + "\n";
  s += "#SBATCH --array=0-" + std::to_string(first_array - 1) + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(suite.slurm.cpus_per_task) + "\n";
  s += "#SBATCH --time=" + sbatchValue(suite.slurm.time) + "\n";
  s += "#SBATCH --mem=" + sbatchValue(suite.slurm.mem) + "\n";
  if (!suite.slurm.partition.empty()) {
    s += "#SBATCH --partition=" + sbatchValue(suite.slurm.partition) + "\n";
  }
  s +=
      "#SBATCH --output=" + sbatchValue(slurmFilenamePattern(dir) + "/logs/slurm-%A_%a.out") + "\n";
  for (const auto& option : suite.slurm.options) s += "#SBATCH " + option + "\n";
  s += "set -eu\n";
  s += "offset=${1:-0}\n";
  s += "cell=$(sed -n \"$((offset + SLURM_ARRAY_TASK_ID + 1))p\" " +
       shellQuote(dir + "/" + kSlurmCellsFile) + ")\n";
  s += "exec " + shellQuote(isg) + " sweep --cell \"$cell\" " + shellQuote(dir) + "\n";
  return s;
}

std::string writeSlurmScript(const std::string& sweep_dir, const Suite& suite,
                             const std::vector<std::size_t>& pending, const std::string& isg,
                             std::size_t max_array_size) {
  std::string list;
  for (std::size_t i : pending) list += std::to_string(i) + "\n";
  fs::create_directories(fs::path(sweep_dir) / "logs");
  common::writeFileAtomically((fs::path(sweep_dir) / kSlurmCellsFile).string(), list);
  const std::string script = (fs::path(sweep_dir) / kSlurmScriptFile).string();
  common::writeFileAtomically(script,
                              slurmScript(sweep_dir, suite, pending.size(), isg, max_array_size));
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  return script;
}

std::size_t slurmMaxArraySize() {
  // Bounded: scontrol retries a controller that does not answer for minutes.
  FILE* pipe = popen("timeout 30 scontrol show config 2>/dev/null", "r");
  if (pipe == nullptr) return kSlurmDefaultMaxArraySize;
  std::size_t found = 0;
  std::array<char, 4096> line{};
  while (std::fgets(line.data(), int(line.size()), pipe) != nullptr) {
    // "MaxArraySize            = 1001"
    unsigned long value = 0;
    if (std::sscanf(line.data(), " MaxArraySize = %lu", &value) == 1) found = value;
  }
  pclose(pipe);
  // MaxArraySize 0 disables arrays; a site that does that cannot run the backend at all, and
  // sbatch will say so. 1 allows only index 0: one task per array.
  return found > 0 ? found : kSlurmDefaultMaxArraySize;
}

std::vector<SlurmArray> slurmArrays(std::size_t tasks, std::size_t max_array_size) {
  const std::size_t most = std::max<std::size_t>(1, max_array_size);
  std::vector<SlurmArray> arrays;
  for (std::size_t offset = 0; offset < tasks; offset += most) {
    arrays.push_back({offset, std::min(most, tasks - offset)});
  }
  return arrays;
}

std::string sbatchCommand(const std::string& script, const SlurmArray& array,
                          const std::string& options) {
  return "sbatch " + (options.empty() ? "" : options + " ") + "--array=0-" +
         std::to_string(array.count - 1) + " " + shellQuote(script) + " " +
         std::to_string(array.offset);
}

std::vector<std::string> submitSlurm(const std::string& script,
                                     const std::vector<SlurmArray>& arrays, bool wait) {
  // Every sbatch is started before any is read: with --wait each blocks until its array ends,
  // and the arrays run side by side.
  std::vector<FILE*> pipes;
  for (const auto& array : arrays) {
    const std::string command =
        sbatchCommand(script, array, wait ? "--parsable --wait" : "--parsable") + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
      for (FILE* p : pipes) pclose(p);
      throw common::InputError(script, "", "cannot start sbatch");
    }
    pipes.push_back(pipe);
  }
  std::vector<std::string> ids;
  std::string refused;
  for (FILE* pipe : pipes) {
    std::string output;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), int(buffer.size()), pipe) != nullptr) output += buffer.data();
    const int status = pclose(pipe);
    while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 127) {
      refused = "sbatch not found: is this a Slurm submission host?";
      continue;
    }
    // With --wait, sbatch's exit code is the job's (non-zero when a task failed); the job id is
    // its first line either way. Without it, a non-zero code means the submission was refused.
    const std::string first = output.substr(0, output.find('\n'));
    const bool id = !first.empty() && first.find_first_not_of("0123456789;") == std::string::npos;
    if (!id) {
      if (refused.empty()) refused = "sbatch refused it: " + output;
      continue;
    }
    ids.push_back(first.substr(0, first.find(';')));
  }
  if (!refused.empty()) {
    std::string submitted;
    for (const auto& id : ids) submitted += (submitted.empty() ? "" : ", ") + id;
    throw common::InputError(
        script, "",
        refused + (ids.empty() ? ""
                               : " (the other arrays were submitted as job " + submitted +
                                     ": scancel them or let them run)"));
  }
  return ids;
}

}  // namespace isg::sweep
