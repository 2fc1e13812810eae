#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/json_reader.hpp"
#include "run/localizer_registry.hpp"
#include "worlds/plan_generator.hpp"

namespace isg::sweep {

// A sweep suite ("isg.suite" v1, docs/sweeps.md): worlds × seeds × methods and how to run them.

struct SuiteWorld {
  std::string name;   // the table's row and the folder of its runs
  std::string input;  // what isg run reads: "builtin:NAME" or an absolute path; generated worlds:
                      // "worlds/<name>.asbuilt.json", relative to the sweep folder
  std::optional<worlds::GeneratorSpec> generate;
  std::string hash;  // worlds::worldHash, once the sweep has read (or written) the world
};

struct SlurmSettings {
  int cpus_per_task = 1;
  std::string time = "01:00:00";     // sbatch --time
  std::string mem = "4G";            // sbatch --mem
  std::string partition;             // empty: the cluster's default
  std::vector<std::string> options;  // more sbatch options, written as given ("--qos=low")
  // Tasks per array at most; unset: the cluster's MaxArraySize (slurmMaxArraySize()).
  std::optional<std::size_t> max_array_size;
};

struct Suite {
  std::string file;  // where it was read from
  std::string name;
  std::vector<SuiteWorld> worlds;
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> methods;  // canonical names
  std::optional<double> duration;    // isg run --duration
  int threads = 1;                   // isg run --threads
  bool start_pose_truth = false;     // isg run --start-pose truth
  std::map<std::string, std::map<std::string, std::string>> method_options;  // method → KEY → VALUE
  // Every method's options with the values its runs use, given or default (what sweep.json
  // records): method → KEY → value.
  std::map<std::string, std::map<std::string, double>> effective_options;
  SlurmSettings slurm;
};

inline constexpr const char* kSuiteFormat = "isg.suite";
inline constexpr int kSuiteVersion = 1;

// Reads and checks a suite; errors are InputErrors naming the file, the JSON pointer and what is
// wrong (an unknown method, a world file that does not exist, a repeated world name ...).
Suite loadSuite(const std::string& path, const run::LocalizerRegistry& methods);
// The same from a document already read; `path` names it and anchors its relative world files.
Suite parseSuite(const common::JsonNode& root, const std::string& path,
                 const run::LocalizerRegistry& methods);

// At most this many cells (worlds × methods × seeds) in one sweep: more is an error naming the
// count, before anything is written (a sweep of millions of runs is several sweeps).
inline constexpr std::uint64_t kMaxSweepCells = 1000000;

// One run of the sweep.
struct SweepCell {
  std::string world, method;
  std::uint64_t seed = 0;
  std::string dir;                     // "<world>/<method>/seed-<n>", relative to the sweep folder
  std::vector<std::string> arguments;  // isg's arguments for it, from "run" on
  std::string world_hash;  // what its metrics.json must say (empty: a sweep.json without hashes)
};

// The cells in world, method, seed order; paths in the arguments are relative to the sweep
// folder (isg run is started there). Each cell carries its world's hash (empty until set).
std::vector<SweepCell> sweepCells(const Suite& suite);

// SWEEP_DIR/sweep.json ("isg.sweep" v1): the suite resolved into its cells, written when a sweep
// starts, so that a sweep started again, a Slurm task and --collect all see the same cells.
inline constexpr const char* kSweepPlanFile = "sweep.json";
// The other files at the top of a sweep folder: the table at the end, the Slurm backend's script
// and its list of cells. With sweep.json, names no world may take (its run folders go beside).
inline constexpr const char* kSweepTableMarkdownFile = "table.md";
inline constexpr const char* kSweepTableCsvFile = "table.csv";
inline constexpr const char* kSlurmScriptFile = "sweep.sbatch";
inline constexpr const char* kSlurmCellsFile = "slurm-cells.txt";
// The folders of the sweep's own: the children's logs, generated worlds, cells moved aside.
inline constexpr const char* kSweepLogsFolder = "logs";
inline constexpr const char* kSweepWorldsFolder = "worlds";
inline constexpr const char* kSweepAsideFolder = ".aside";
// The lock a running sweep holds (its pid inside), and the output marker.
inline constexpr const char* kSweepLockFile = ".lock";
inline constexpr std::array<const char*, 10> kSweepFolderFiles = {
    kSweepPlanFile,     kSweepTableMarkdownFile, kSweepTableCsvFile,
    kSlurmScriptFile,   kSlurmCellsFile,         kSweepLogsFolder,
    kSweepWorldsFolder, kSweepAsideFolder,       kSweepLockFile,
    ".isg-output"};
std::string sweepPlanJson(const Suite& suite, const std::vector<SweepCell>& cells);
// A generator spec as sweep.json records it (every parameter, by the suite's names).
nlohmann::json generatorSpecJson(const worlds::GeneratorSpec& spec);
struct SweepPlan {
  std::string name, suite_file;
  std::vector<SweepCell> cells;
  // Per world name: its content hash and, for a generated world, its generator spec (as JSON);
  // empty for a sweep.json written before they were recorded.
  std::map<std::string, std::string> world_hashes;
  std::map<std::string, nlohmann::json> world_specs;
};
// Reads SWEEP_DIR/sweep.json; a missing or foreign file is an InputError naming it.
SweepPlan readSweepPlan(const std::string& sweep_dir);
// The same from a document already read.
SweepPlan parseSweepPlan(const common::JsonNode& root);

}  // namespace isg::sweep
