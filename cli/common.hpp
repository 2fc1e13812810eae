#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bim/input_error.hpp"
#include "bim/scenario.hpp"

namespace isg::cli {

// Exit codes of every subcommand (ARCHITECTURE.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;

// Loads a plan or scenario (a file or "builtin:NAME") and prints its warnings to stderr.
bim::Scenario loadInput(const std::string& argument, const std::string& command);

// Writes `content` to `path` so that a reader never sees a half-written file: to a temporary
// file beside it, then renamed over it. A failure is an InputError naming the path.
void writeFileAtomically(const std::string& path, const std::string& content);

// The text listing the built-in worlds, for --help.
std::string builtinWorldsHelp();

// A subcommand: registers its options on construction, runs after a successful parse.
class Command {
 public:
  virtual ~Command() = default;
  virtual int run() = 0;
  CLI::App* app() const { return app_; }

 protected:
  CLI::App* app_ = nullptr;
};

}  // namespace isg::cli
