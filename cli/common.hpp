#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bim/input_error.hpp"
#include "bim/scenario.hpp"
#include "run/atomic_folder.hpp"

namespace isg::cli {

using run::writeFileAtomically;

// Exit codes of every subcommand (docs/architecture.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;

// Loads a plan or scenario (a file or "builtin:NAME") and prints its warnings to stderr.
bim::Scenario loadInput(const std::string& argument, const std::string& command);

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
