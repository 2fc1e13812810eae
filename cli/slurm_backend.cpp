#include "cli/slurm_backend.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>

#include "bim/input_error.hpp"
#include "run/atomic_folder.hpp"

namespace isg::cli {

namespace {

namespace fs = std::filesystem;

// A word for bash: in single quotes, each single quote written '\''.
std::string shellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string slurmScript(const std::string& sweep_dir, const Suite& suite, std::size_t tasks,
                        const std::string& isg) {
  const std::string dir = fs::absolute(sweep_dir).lexically_normal().string();
  std::string s = "#!/bin/bash\n";
  s += "# Written by isg sweep --backend slurm (docs/sweeps.md): one array task per cell left to\n";
  s += "# run; task T runs the cell on line T+1 of slurm-cells.txt. Submit again with\n";
  s += "# isg sweep SUITE -o SWEEP_DIR --backend slurm: finished cells are left out.\n";
  s += "#SBATCH --job-name=isg-" + suite.name + "\n";
  s += "#SBATCH --array=0-" + std::to_string(tasks == 0 ? 0 : tasks - 1) + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(suite.slurm.cpus_per_task) + "\n";
  s += "#SBATCH --time=" + suite.slurm.time + "\n";
  s += "#SBATCH --mem=" + suite.slurm.mem + "\n";
  if (!suite.slurm.partition.empty()) s += "#SBATCH --partition=" + suite.slurm.partition + "\n";
  s += "#SBATCH --output=" + dir + "/logs/slurm-%A_%a.out\n";
  for (const auto& option : suite.slurm.options) s += "#SBATCH " + option + "\n";
  s += "set -eu\n";
  s += "cell=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " + shellQuote(dir + "/slurm-cells.txt") +
       ")\n";
  s += "exec " + shellQuote(isg) + " sweep --cell \"$cell\" " + shellQuote(dir) + "\n";
  return s;
}

std::string writeSlurmScript(const std::string& sweep_dir, const Suite& suite,
                             const std::vector<std::size_t>& pending, const std::string& isg) {
  std::string list;
  for (std::size_t i : pending) list += std::to_string(i) + "\n";
  fs::create_directories(fs::path(sweep_dir) / "logs");
  run::writeFileAtomically((fs::path(sweep_dir) / "slurm-cells.txt").string(), list);
  const std::string script = (fs::path(sweep_dir) / "sweep.sbatch").string();
  run::writeFileAtomically(script, slurmScript(sweep_dir, suite, pending.size(), isg));
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  return script;
}

std::string submitSlurm(const std::string& script, bool wait) {
  const std::string command = std::string("sbatch --parsable") + (wait ? " --wait" : "") + " " +
                              shellQuote(script) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw bim::InputError(script, "", "cannot start sbatch");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), int(buffer.size()), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 127) {
    throw bim::InputError(script, "", "sbatch not found: is this a Slurm submission host?");
  }
  // With --wait, sbatch's exit code is the job's (non-zero when a task failed); the job id is
  // its first line either way. Without it, a non-zero code means the submission was refused.
  const std::string first = output.substr(0, output.find('\n'));
  const bool id = !first.empty() && first.find_first_not_of("0123456789;") == std::string::npos;
  if (!id) throw bim::InputError(script, "", "sbatch refused it: " + output);
  return first.substr(0, first.find(';'));
}

}  // namespace isg::cli
