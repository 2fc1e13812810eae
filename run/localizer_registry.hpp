#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"
#include "slam/localizer.hpp"

namespace isg::run {

// Everything a method may be built from. A method takes what it needs and ignores the rest.
struct LocalizerContext {
  const bim::Plan* plan = nullptr;      // the plan to localize in, when there is one
  const bim::AGraph* agraph = nullptr;  // its A-Graph
  std::string level;                    // the level the robot walks
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();  // the LiDAR on the base
  Eigen::Isometry3d R_T_I = Eigen::Isometry3d::Identity();  // the IMU on the base
  // The start hint: where M lies in B at the start (the true start pose). Only methods that are
  // given their start (dead reckoning, trackers) read it; global localizers never do.
  std::optional<Eigen::Isometry3d> start_B_T_M;
  // A start pose given to a global localizer (--start-pose): where M lies in B at the start, as
  // an operator (or a benchmark's first pose) gives it. Methods that take one (MethodInfo::
  // takes_start_pose) start localized there and check it as they check any match.
  std::optional<Eigen::Isometry3d> given_start_B_T_M;
  // ... or given at a later instant (a benchmark's start pose, about 5 s into the run): the base's
  // pose in B at `stamp` (the run's clock); the method makes it B_T_M with its own odometry there.
  struct StampedStart {
    double stamp = 0.0;
    Eigen::Isometry3d B_T_R = Eigen::Isometry3d::Identity();
  };
  std::optional<StampedStart> given_start_at;
  // The run's seed: methods that draw at random (particle filters, a perturbed start) draw from
  // a generator seeded with it, so a run is reproducible.
  std::uint64_t seed = 0;
  // Threads the method may use for its own work (--threads); its results never depend on it.
  int threads = 1;
  // Settings from --method-option KEY=VALUE (run/method_options.hpp): each method reads its own
  // and rejects the keys it does not know.
  std::map<std::string, std::string> options;
};

// A localization method as the command line offers it.
struct MethodInfo {
  std::string name = {};     // what --method takes
  std::string summary = {};  // one line for --help
  bool needs_plan = false;
  bool given_start = false;       // reads LocalizerContext::start_B_T_M
  bool takes_start_pose = false;  // reads LocalizerContext::given_start_B_T_M / _at if given
  // SLAM only: never localizes in B; tables show its map-frame APE after SE(3) alignment.
  bool slam_only = false;
  std::function<std::unique_ptr<slam::Localizer>(const LocalizerContext&)> make = {};
  // Reads the options as make() does, without a world: throws std::invalid_argument for a bad
  // value or a key the method does not know; returns every option the method has with the value
  // it will use (MethodOptions::effective). Empty: the method takes no options.
  std::function<std::map<std::string, double>(const std::map<std::string, std::string>&)>
      check_options = {};
  // Older names --method still takes for it (a renamed method keeps its command line working).
  std::vector<std::string> aliases = {};
};

// The methods a run can use, by name, in the order they were added (the order of tables'
// columns). A new method adds itself with add(); nothing else in the pipeline names methods.
class LocalizerRegistry {
 public:
  // Throws std::invalid_argument when the name is taken or the entry has no factory.
  void add(MethodInfo method);
  // The method with this name or alias, or nullptr.
  const MethodInfo* find(const std::string& name) const;
  std::vector<std::string> names() const;
  // names() and every alias: what --method accepts.
  std::vector<std::string> acceptedNames() const;
  // The method's name for a name or alias; an unknown name unchanged (old run folders).
  std::string canonical(const std::string& name) const;
  // Throws std::invalid_argument (naming the key) when the method does not take these options:
  // a sweep checks a suite's options before any run, make() checks them too. Returns each of
  // the method's options with the value it will use (given, else its default): what metrics.json
  // and sweep.json record.
  std::map<std::string, double> checkOptions(
      const std::string& name, const std::map<std::string, std::string>& options) const;
  // "  is-graphs: …\n  s-graph: …" for --help (aliases in parentheses).
  std::string help() const;
  // Builds the method. Throws std::invalid_argument for an unknown name, options the method does
  // not take, or when the method needs a plan (or a start) that the context lacks: the caller
  // checks find() first.
  std::unique_ptr<slam::Localizer> make(const std::string& name,
                                        const LocalizerContext& context) const;

 private:
  std::vector<MethodInfo> methods_;
};

}  // namespace isg::run
