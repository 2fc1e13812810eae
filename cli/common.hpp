#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bim/scenario.hpp"
#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"

namespace isg::cli {

using common::writeFileAtomically;

// Exit codes of every subcommand (docs/architecture.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;
// isg table --baseline: a cell is worse than its baseline.
inline constexpr int kExitRegression = 4;
// isg sweep: some cell failed or has not run (the table holds the others).
inline constexpr int kExitIncomplete = 5;

// Option checks with plain messages ("--duration: must be > 0, got -1"), for finite numbers.
CLI::Validator positiveNumber();
CLI::Validator nonNegativeNumber();
// A decimal number within [min, max] ("--resolution: expected a number 0.0001 … 10, got nan"):
// CLI::Range alone lets NaN through, and CLI11 reads "0x10" as sixteen.
CLI::Validator numberIn(double min, double max);
// A seed as the suite reader takes it: a decimal integer 0 … 2^64 − 1, no sign (CLI11 alone would
// wrap "-1" and 2^64 silently).
CLI::Validator seedNumber();

// --lidar MODEL (isg simulate, isg run): the scenario's LiDAR replaced by another model, with that
// model's range gate, noise and detection range (bim/lidar_models.hpp).
void addLidarModelOption(CLI::App& app, std::string& model);
// The option's effect on a loaded scenario (nothing when `model` is empty).
void useLidarModelOption(bim::Scenario& scenario, const std::string& model);

// The file a PLAN|SCENARIO argument names ("" for a built-in world), for the output rule's inputs.
std::string inputFile(const std::string& argument);

// Loads a plan or scenario (a file or "builtin:NAME") and prints its warnings to stderr.
bim::Scenario loadInput(const std::string& argument, const std::string& command);

// The text listing the built-in worlds, for --help.
std::string builtinWorldsHelp();

// Help text that names positionals as the README does (PLAN|SCENARIO, DATASET_DIR, RUN_DIR):
// a positional with an option_text is shown by that text, in the usage line and in its list.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool is_positional) const override {
    if (is_positional && !option->get_option_text().empty()) return option->get_option_text();
    return CLI::Formatter::make_option_name(option, is_positional);
  }
  std::string make_option_opts(const CLI::Option* option) const override {
    if (!option->nonpositional() && !option->get_option_text().empty()) return "";
    return CLI::Formatter::make_option_opts(option);
  }
};

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
