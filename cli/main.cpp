// isg: the iS-Graphs testbed's command line. Subcommands are thin: they parse flags and call the
// modules. Exit codes: 0 success, 1 bad input (the message names the file, the JSON pointer and
// what is wrong), 2 bad usage, 3 internal error, 128 + N stopped by signal N (Ctrl-C: 130).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "cli/cmd_agraph.hpp"
#include "cli/cmd_bcf.hpp"
#include "cli/cmd_check.hpp"
#include "cli/cmd_eval.hpp"
#include "cli/cmd_export.hpp"
#include "cli/cmd_generate.hpp"
#include "cli/cmd_import.hpp"
#include "cli/cmd_inspect.hpp"
#include "cli/cmd_render.hpp"
#include "cli/cmd_run.hpp"
#include "cli/cmd_simulate.hpp"
#include "cli/cmd_slam.hpp"
#include "cli/cmd_sweep.hpp"
#include "cli/cmd_table.hpp"
#include "cli/cmd_vlp16.hpp"
#include "cli/cmd_world.hpp"
#include "common/input_error.hpp"
#include "run/interrupt.hpp"

int main(int argc, char** argv) {
  using namespace isg::cli;
  CLI::App app{
      "isg: a simulation-in-the-loop testbed for global localization of a legged robot against "
      "architectural plans (iS-Graphs).",
      "isg"};
  app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands: they inherit it
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", std::string("isg 0.1.0"));
  app.footer("Run 'isg COMMAND --help' for the options of a command.");

  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<WorldCommand>(app));
  commands.push_back(std::make_unique<CheckCommand>(app));
  commands.push_back(std::make_unique<ImportCommand>(app));
  commands.push_back(std::make_unique<GenerateCommand>(app));
  commands.push_back(std::make_unique<InspectCommand>(app));
  commands.push_back(std::make_unique<AGraphCommand>(app));
  commands.push_back(std::make_unique<SimulateCommand>(app));
  commands.push_back(std::make_unique<ExportCommand>(app));
  commands.push_back(std::make_unique<RenderCommand>(app));
  commands.push_back(std::make_unique<SlamCommand>(app));
  commands.push_back(std::make_unique<RunCommand>(app));
  commands.push_back(std::make_unique<EvalCommand>(app));
  commands.push_back(std::make_unique<TableCommand>(app));
  commands.push_back(std::make_unique<BcfCommand>(app));
  commands.push_back(std::make_unique<SweepCommand>(app));
  commands.push_back(std::make_unique<Vlp16Command>(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "isg: " << e.what() << "\n";
    std::cerr << "Run 'isg --help' (or 'isg COMMAND --help') for usage.\n";
    return kExitUsage;
  }

  isg::run::installInterruptHandlers();
  for (const auto& command : commands) {
    if (!command->app()->parsed()) continue;
    const std::string name = command->app()->get_name();
    try {
      return command->run();
    } catch (const isg::run::Interrupted& e) {
      std::cerr << "isg " << name << ": " << e.what() << "; nothing was written\n";
      return 128 + e.signalNumber();
    } catch (const isg::common::InputError& e) {
      std::cerr << "isg " << name << ": error: " << e.what() << "\n";
      return kExitBadInput;
    } catch (const std::filesystem::filesystem_error& e) {
      // A path the user gave that the system cannot follow (a symlink loop, no permission, a
      // full disk) where a check did not catch it first: their input, named, not our bug.
      const std::string path = e.path1().empty() ? std::string() : e.path1().string() + ": ";
      std::cerr << "isg " << name << ": error: " << path << e.code().message() << "\n";
      return kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "isg " << name << ": internal error: " << e.what() << "\n";
      return kExitInternal;
    }
  }
  return kExitUsage;
}
