#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "common/input_error.hpp"

namespace isg::ifc {

// isg import MODEL.ifc: an IFC2X3 or IFC4 building model read as a plan v1 (docs/formats.md,
// "Importing IFC", states every rule below and why).

// The largest model read (the whole file is held in memory, as IFC++ needs).
inline constexpr std::uintmax_t kMaxIfcBytes = 512ull << 20;

struct ImportOptions {
  // Storeys to import by name; empty: every storey with walls standing on it and rooms (or with
  // walls, when no storey has rooms).
  std::vector<std::string> storeys;
};

// What became of one building storey.
struct StoreySummary {
  std::string name;
  std::string global_id;
  double elevation = 0.0;
  std::string level_id;  // "" when not imported
  std::string why_not;   // why it is not a level
  int walls = 0, walls_from_other_storeys = 0, doors = 0, windows = 0, rooms = 0;
  int spaces = 0;   // IfcSpace in the storey
  int columns = 0;  // IfcColumn standing on its floor
};

struct ImportResult {
  nlohmann::ordered_json plan_json;  // the plan file: parsed by bim's parser before it is returned
  bim::Plan plan;
  common::Warnings warnings;  // the parser's, on the plan written
  std::string schema;         // IFC2X3 or IFC4
  std::string application;    // the authoring tool, from the header
  double metres_per_unit = 1.0;
  // One line per element dropped or simplified, naming it by GlobalId and name and saying why.
  std::vector<std::string> log;
  std::vector<StoreySummary> storeys;
  // IFC++'s own error messages while reading (geometry it could not build, for instance).
  std::vector<std::string> reader_errors;
};

// The import was stopped by a signal (Ctrl-C) while IFC++ read the model; nothing was written.
class ImportInterrupted : public std::runtime_error {
 public:
  explicit ImportInterrupted(int signal);
  int signalNumber() const { return signal_; }

 private:
  int signal_;
};

// Reads `path` (a regular file of at most kMaxIfcBytes). IFC++ runs in a child process: a model
// that makes it crash is reported like any bad model. Throws common::InputError naming the file
// for a file that is missing, not IFC, truncated, of another schema, has no IfcProject, no
// storey, no wall in the storeys imported, or names a storey it does not have.
ImportResult importIfc(const std::string& path, const ImportOptions& options);

// The same from the file's text; `file` names it in messages (the fuzz harness's entry point).
ImportResult importIfcText(const std::string& file, std::string text, const ImportOptions& options);

}  // namespace isg::ifc
