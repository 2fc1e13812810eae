#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace isg::cli::testing {

// Runs the real isg executable in a scratch directory, as a user would, and captures what it
// prints and its exit code.
struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

class Sandbox {
 public:
  explicit Sandbox(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() / ("isg_cli_test_" + name)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~Sandbox() { std::filesystem::remove_all(dir_); }

  const std::filesystem::path& dir() const { return dir_; }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }

  bool exists(const std::string& name) const { return std::filesystem::exists(dir_ / name); }

  std::string read(const std::string& name) const {
    std::ifstream in(dir_ / name, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  // `arguments` is passed to a shell, after `cd` into the sandbox (or its folder `subdir`).
  RunResult run(const std::string& arguments, const std::string& subdir = "") const {
    const std::string out = (dir_ / ".stdout").string(), err = (dir_ / ".stderr").string();
    const std::string command = "cd '" + (dir_ / subdir).string() + "' && '" +
                                std::string(ISG_EXECUTABLE) + "' " + arguments + " > '" + out +
                                "' 2> '" + err + "' < /dev/null";
    const int status = std::system(command.c_str());
    RunResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read(".stdout");
    result.err = read(".stderr");
    std::filesystem::remove(dir_ / ".stdout");
    std::filesystem::remove(dir_ / ".stderr");
    return result;
  }

  // Every file the sandbox holds, for "nothing was written" checks.
  std::size_t fileCount() const {
    std::size_t n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      (void)entry;
      ++n;
    }
    return n;
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace isg::cli::testing
