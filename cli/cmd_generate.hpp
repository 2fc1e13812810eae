#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "worlds/plan_generator.hpp"

namespace isg::cli {

// isg generate FAMILY... -o DIR: procedural plans and as-built scenarios (worlds/plan_generator).
class GenerateCommand : public Command {
 public:
  explicit GenerateCommand(CLI::App& parent);
  int run() override;

 private:
  // The option table, by group (the constructor adds the rest).
  void addLayoutOptions();
  void addAsBuiltOptions();
  // The steps of run(): the families asked for (each once), the options that do not apply to
  // them said, the buildings made, and each written (and checked, unless --no-verify).
  std::vector<std::string> familiesAsked() const;
  void warnOfOptionsThatDoNotApply(const std::vector<std::string>& families) const;
  std::vector<worlds::GeneratedBuilding> makeBuildings(
      const std::vector<std::string>& families) const;
  void writeAndCheck(const worlds::GeneratedBuilding& building,
                     const std::filesystem::path& dir) const;

  std::vector<std::string> families_;
  std::string output_;
  int count_ = 1;
  std::uint64_t seed_ = 1;
  worlds::GeneratorSpec spec_;
  bool symmetric_ = false;
  bool no_verify_ = false;
  bool force_ = false;
  bool quiet_ = false;
};

}  // namespace isg::cli
