#pragma once

#include <string>
#include <vector>

#include "cli/common.hpp"

namespace isg::cli {

// isg import MODEL.ifc -o PLAN.json: an IFC building model as a plan (docs/formats.md,
// "Importing IFC").
class ImportCommand : public Command {
 public:
  explicit ImportCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string output_;
  std::vector<std::string> storeys_;
  bool force_ = false;
  bool quiet_ = false;
};

}  // namespace isg::cli
