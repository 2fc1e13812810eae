#include "cli/common.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "worlds/reference_plans.hpp"

namespace isg::cli {

bim::Scenario loadInput(const std::string& argument, const std::string& command) {
  bim::Warnings warnings;
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin(argument, &warnings);
  for (const auto& w : warnings) std::cerr << "isg " << command << ": warning: " << w.str() << "\n";
  return scenario;
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) {
    throw bim::InputError(path, "", "cannot write: directory " + dir.string() + " does not exist");
  }
  const fs::path temporary =
      dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw bim::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
    }
    out << content;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw bim::InputError(path, "", "cannot write: write failed");
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw bim::InputError(path, "", "cannot write: " + error.message());
  }
}

std::string builtinWorldsHelp() {
  std::string names;
  for (const auto& n : worlds::builtinNames()) names += (names.empty() ? "" : ", ") + n;
  return "PLAN|SCENARIO is a file in the isg.plan or isg.scenario format (docs/formats.md), or a "
         "built-in world written builtin:NAME, NAME one of: " +
         names + ".";
}

}  // namespace isg::cli
