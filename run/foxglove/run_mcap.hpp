#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/pose_track.hpp"
#include "common/tum.hpp"
#include "formats/mcap_writer.hpp"
#include "formats/ros_time.hpp"
#include "run/foxglove/growing_path.hpp"
#include "sensors/messages.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// A run as an MCAP file to watch in Foxglove (docs/foxglove.md): the plan, the A-Graph, the
// S-Graph over time, matching, paths, scans, transforms and deviations, as Foxglove's JSON
// messages (the scans as ROS 2 CDR PointCloud2).

inline constexpr char kRunTfTopic[] = "/tf";
inline constexpr char kRunPlanTopic[] = "/plan";
inline constexpr char kRunAGraphTopic[] = "/agraph";
inline constexpr char kRunSGraphTopic[] = "/sgraph";
inline constexpr char kRunMatchingTopic[] = "/isg/matching";
inline constexpr char kRunCandidatesTopic[] = "/isg/candidates";
inline constexpr char kRunLogTopic[] = "/isg/log";
inline constexpr char kRunGroundTruthPathTopic[] = "/groundtruth/path";
inline constexpr char kRunEstimatePathTopic[] = "/estimate/path";
inline constexpr char kRunEstimateMapPathTopic[] = "/estimate_map/path";
inline constexpr char kRunScanTopic[] = "/velodyne_points";
inline constexpr char kRunDeviationsTopic[] = "/deviations";

struct RunMcapOptions {
  formats::McapCompression compression = formats::McapCompression::kZstd;
  bool overwrite = false;
  // Whole seconds added to every run time, as in the dataset's MCAP file (McapExportOptions), so
  // that a run and its dataset open side by side in Foxglove.
  std::uint32_t stamp_offset = 1000000000;
  // Robot seconds between the S-Graph, matching and path messages, and between the scans kept:
  // each is a whole state, so a file grows with the square of the run's length over this.
  double snapshot_period = 1.0;
  bool scans = true;  // a /velodyne_points channel (a run folder keeps no scans)
};

// Whether a snapshot is due at `stamp`, the last one having been at `last` (none yet: due).
bool snapshotDue(const std::optional<double>& last, double stamp, double period);

// A change of the matcher's status (metrics.json's matching_events).
struct MatchingEvent {
  double stamp = 0.0;
  int keyframe = 0;
  std::string status, reason;
};

// What a run knows after one scan.
struct RunMoment {
  double stamp = 0.0;
  std::optional<Eigen::Isometry3d> M_T_R;  // the estimate in the map frame
  std::optional<Eigen::Isometry3d> B_T_M;  // where the map lies in the plan, once known
  // The method's graph (sgraph.json's form) when snapshotDue(stamp) said so; else null.
  const nlohmann::json* graph = nullptr;
  std::vector<MatchingEvent> events;  // the status changes since the last moment
};

// Writes a run's MCAP file as the run goes, in time order: what is known from the start (the plan,
// the A-Graph, the ground truth path, the LiDAR's mount) at the first moment; transforms and the
// estimate after each scan; the S-Graph, matching and paths every snapshot_period, and the scans
// the caller keeps (one per snapshot: LiveRunMcap); the
// final graph and the deviations at finish(). The file appears at `path` only when finish()
// returns (formats::McapWriter).
class RunMcapWriter {
 public:
  // `agraph`: agraph.json's document, or null for a run without a plan. `R_T_L`: the LiDAR on the
  // base, when known. `ground_truth`: B_T_R, possibly empty.
  RunMcapWriter(const std::string& path, const RunMcapOptions& options,
                const nlohmann::json* agraph, std::optional<Eigen::Isometry3d> R_T_L,
                common::PoseSequence ground_truth);

  // Whether the moment at `stamp` should carry a graph snapshot and a scan.
  bool snapshotDue(double stamp) const;
  // Call after each new estimate, in time order.
  void add(const RunMoment& moment);
  // A scan the localizer read, in the LiDAR's frame at its own stamp (the turn's first firing).
  void addScan(const sensors::Scan& scan);
  // The final graph (sgraph.json) and the deviation report (or null), at the last moment's
  // stamp; closes the file.
  void finish(const nlohmann::json& final_graph, const slam::DeviationReport* deviations);

  // Messages per topic so far.
  std::vector<std::pair<std::string, std::uint64_t>> counts() const;

 private:
  formats::RosTime time(double stamp) const;
  void writeJson(const std::string& topic, double stamp, const nlohmann::json& message);
  void writeText(const std::string& topic, double stamp, const std::string& text);
  void start(double stamp);
  void writeSnapshot(double stamp, const nlohmann::json& graph);
  void writePaths(double stamp);

  RunMcapOptions options_;
  formats::McapWriter mcap_;
  std::vector<std::pair<std::string, std::uint16_t>> channels_;
  const nlohmann::json* agraph_;
  std::optional<Eigen::Isometry3d> R_T_L_;
  GrowingPath ground_truth_path_, estimate_path_, estimate_map_path_;
  bool started_ = false;
  std::optional<double> last_snapshot_;
  double last_stamp_ = 0.0;
};

// Writes a finished run folder (docs/evaluation.md) as the MCAP file of RunMcapWriter: the
// moments from estimate_map.tum and estimate.tum, the status changes from metrics.json. A run
// folder keeps no scans and only the final graph: the file has no /velodyne_points, and /sgraph
// carries the keyframes as they were made with the planes they had observed, and the whole graph
// at the end (docs/foxglove.md). Bad input is an InputError naming the file.
struct RunExportSummary {
  std::vector<std::pair<std::string, std::uint64_t>> counts;
  double seconds = 0.0;  // robot time covered
};
RunExportSummary exportRunMcap(const std::string& run_dir, const std::string& mcap_path,
                               const RunMcapOptions& options);

// Whether `dir` is a run folder (it has metrics.json and estimate_map.tum).
bool isRunFolder(const std::string& dir);

}  // namespace isg::run
