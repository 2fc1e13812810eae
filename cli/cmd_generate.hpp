#pragma once

#include <cstdint>
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
