#include "run/foxglove/run_mcap.hpp"

#include <filesystem>
#include <set>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "formats/foxglove_json.hpp"
#include "formats/ros2_messages.hpp"
#include "formats/trajectory_file.hpp"
#include "run/deviation_report_reader.hpp"
#include "run/foxglove/run_scene.hpp"

namespace isg::run {

namespace {

namespace fx = formats::foxglove;
using Json = nlohmann::json;

// A path keeps a pose once the robot has moved this far from the last one kept (and always the
// latest): Foxglove draws it as a line, and a path message holds the whole path so far.
constexpr double kPathSpacing = 0.1;  // m

// The frames of the tree plan → map → base_link → velodyne.
constexpr char kPlanFrame[] = "plan";
constexpr char kMapFrame[] = "map";
constexpr char kBaseFrame[] = "base_link";
constexpr char kLidarFrame[] = "velodyne";

// The schema of /isg/matching: the matcher's state as sgraph.json's "matching" holds it
// (docs/matching.md), stamped. Only the fields every state has are required.
std::string matchingSchema() {
  const Json number = {{"type", "number"}};
  const Json pose2d = {
      {"type", "object"},
      {"properties", {{"x", number}, {"y", number}, {"z", number}, {"yaw", number}}}};
  const Json schema = {
      {"$schema", "http://json-schema.org/draft-07/schema#"},
      {"title", "isg.Matching"},
      {"description",
       "The iS-Graph matcher's state: its status, where it places the map in the plan, which "
       "S-Graph rooms and planes it matched to which A-Graph rooms and wall surfaces, and its last "
       "attempt with the candidates it weighed (docs/matching.md)."},
      {"type", "object"},
      {"properties",
       {{"timestamp",
         {{"type", "object"},
          {"properties",
           {{"sec", {{"type", "integer"}, {"minimum", 0}}},
            {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}}},
          {"required", {"sec", "nsec"}}}},
        {"status", {{"type", "string"}}},
        {"localized", {{"type", "boolean"}}},
        {"level", {{"type", "string"}}},
        {"B_T_M", pose2d},
        {"room_matches", {{"type", "array"}}},
        {"plane_matches", {{"type", "array"}}},
        {"released_walls", {{"type", "array"}}},
        {"events", {{"type", "array"}}},
        {"last_match", {{"type", "object"}}}}},
      {"required", {"timestamp", "status", "localized"}}};
  return schema.dump();
}

fx::LogLevel levelOf(const std::string& status) {
  return status == "lost" || status == "contradicted" ? fx::LogLevel::kWarning
                                                      : fx::LogLevel::kInfo;
}

// What of the final graph `graph` a run folder can place in time at `t`: the keyframes made by
// then, and the planes they had observed (at their final places); rooms and floors only at the end.
Json graphSoFar(const Json& graph, double t) {
  Json keyframes = Json::array(), planes = Json::array();
  std::set<int> seen;
  for (const Json& keyframe : graph.value("keyframes", Json::array())) {
    if (keyframe.value("stamp", 0.0) > t + 1e-9) continue;
    keyframes.push_back(keyframe);
    for (const Json& id : keyframe.value("plane_ids", Json::array())) seen.insert(id.get<int>());
  }
  for (const Json& plane : graph.value("planes", Json::array())) {
    if (seen.count(plane.value("id", -1))) planes.push_back(plane);
  }
  return {{"keyframes", keyframes}, {"planes", planes}};
}

}  // namespace

RunMcapWriter::RunMcapWriter(const std::string& path, const RunMcapOptions& options,
                             const Json* agraph, std::optional<Eigen::Isometry3d> R_T_L,
                             common::PoseSequence ground_truth)
    : options_(options),
      mcap_(path, {options.compression, 4 << 20, "", options.overwrite}),
      agraph_(agraph),
      R_T_L_(std::move(R_T_L)),
      ground_truth_path_(kPathSpacing),
      estimate_path_(kPathSpacing),
      estimate_map_path_(kPathSpacing) {
  for (const auto& row : ground_truth) ground_truth_path_.add(row.pose);
  const auto add = [&](const std::string& topic, std::uint16_t schema,
                       const std::string& encoding) {
    channels_.emplace_back(topic, mcap_.addChannel(schema, topic, encoding));
  };
  const auto foxglove = [&](const fx::SchemaText& text) {
    return mcap_.addSchema(text.name, "jsonschema", text.json_schema);
  };
  const std::uint16_t tf = foxglove(fx::frameTransformSchema());
  const std::uint16_t scene = foxglove(fx::sceneUpdateSchema());
  const std::uint16_t poses = foxglove(fx::posesInFrameSchema());
  const std::uint16_t log = foxglove(fx::logSchema());
  const std::uint16_t matching = mcap_.addSchema("isg.Matching", "jsonschema", matchingSchema());
  const formats::ros2::MessageType cloud = formats::ros2::pointCloud2Type();
  add(kRunTfTopic, tf, "json");
  if (agraph_) {
    add(kRunPlanTopic, scene, "json");
    add(kRunAGraphTopic, scene, "json");
    add(kRunDeviationsTopic, scene, "json");
    add(kRunCandidatesTopic, scene, "json");
  }
  add(kRunSGraphTopic, scene, "json");
  add(kRunMatchingTopic, matching, "json");
  add(kRunLogTopic, log, "json");
  if (!ground_truth_path_.empty()) add(kRunGroundTruthPathTopic, poses, "json");
  add(kRunEstimatePathTopic, poses, "json");
  add(kRunEstimateMapPathTopic, poses, "json");
  if (options.scans) {
    add(kRunScanTopic, mcap_.addSchema(cloud.name, "ros2msg", cloud.definition), "cdr");
  }
}

formats::RosTime RunMcapWriter::time(double stamp) const {
  return formats::RosTime::fromSeconds(std::max(0.0, stamp), options_.stamp_offset);
}

void RunMcapWriter::writeJson(const std::string& topic, double stamp, const Json& message) {
  writeText(topic, stamp, message.dump());
}

void RunMcapWriter::writeText(const std::string& topic, double stamp, const std::string& text) {
  for (const auto& [name, channel] : channels_) {
    if (name == topic) {
      const formats::RosTime t = time(stamp);
      mcap_.write(channel, std::uint64_t(t.sec) * 1000000000ull + t.nsec, text);
      return;
    }
  }
}

bool snapshotDue(const std::optional<double>& last, double stamp, double period) {
  return !last || stamp >= *last + period - 1e-9;
}

bool RunMcapWriter::snapshotDue(double stamp) const {
  return run::snapshotDue(last_snapshot_, stamp, options_.snapshot_period);
}

void RunMcapWriter::start(double stamp) {
  started_ = true;
  const formats::RosTime t = time(stamp);
  if (R_T_L_) {
    writeJson(kRunTfTopic, stamp, fx::frameTransform(t, kBaseFrame, kLidarFrame, *R_T_L_));
  }
  if (agraph_) {
    writeJson(kRunPlanTopic, stamp, fx::sceneUpdate(planEntities(*agraph_, t)));
    writeJson(kRunAGraphTopic, stamp, fx::sceneUpdate(agraphEntities(*agraph_, t)));
  }
  if (!ground_truth_path_.empty()) {
    writeText(kRunGroundTruthPathTopic, stamp, ground_truth_path_.message(t, kPlanFrame));
  }
}

void RunMcapWriter::add(const RunMoment& moment) {
  if (!started_) start(moment.stamp);
  const double stamp = moment.stamp;
  last_stamp_ = stamp;
  const formats::RosTime t = time(stamp);
  for (const MatchingEvent& event : moment.events) {
    writeJson(kRunLogTopic, stamp,
              fx::log(t, levelOf(event.status),
                      event.status + " (keyframe " + std::to_string(event.keyframe) +
                          "): " + event.reason,
                      "isg.matching"));
  }
  if (moment.B_T_M) {
    writeJson(kRunTfTopic, stamp, fx::frameTransform(t, kPlanFrame, kMapFrame, *moment.B_T_M));
  }
  if (moment.M_T_R) {
    writeJson(kRunTfTopic, stamp, fx::frameTransform(t, kMapFrame, kBaseFrame, *moment.M_T_R));
    estimate_map_path_.add(*moment.M_T_R);
    if (moment.B_T_M) estimate_path_.add(*moment.B_T_M * *moment.M_T_R);
  }
  if (moment.graph) {
    last_snapshot_ = stamp;
    writeSnapshot(stamp, *moment.graph);
    writePaths(stamp);
  }
}

void RunMcapWriter::addScan(const sensors::Scan& scan) {
  const formats::RosTime s = time(scan.stamp);
  const formats::ros2::Time cloud_time{std::int32_t(s.sec), s.nsec};
  const std::string cloud = formats::ros2::pointCloud2(scan.points, cloud_time, kLidarFrame);
  for (const auto& [name, channel] : channels_) {
    if (name == kRunScanTopic) mcap_.write(channel, cloud_time.nanoseconds(), cloud);
  }
}

void RunMcapWriter::writeSnapshot(double stamp, const Json& graph) {
  const formats::RosTime t = time(stamp);
  writeJson(kRunSGraphTopic, stamp, fx::sceneUpdate(sgraphEntities(graph, t)));
  const auto matching = graph.find("matching");
  if (matching != graph.end() && matching->is_object() && matching->contains("status")) {
    Json message = *matching;
    message["timestamp"] = fx::time(t);
    if (!message.contains("localized")) message["localized"] = false;
    // The attempt's wall time (sgraph.json keeps it) would make one seed's files differ.
    if (const auto last = message.find("last_match"); last != message.end() && last->is_object()) {
      last->erase("seconds");
    }
    writeJson(kRunMatchingTopic, stamp, message);
    if (agraph_) {
      writeJson(kRunCandidatesTopic, stamp, fx::sceneUpdate(candidateEntities(graph, *agraph_, t)));
    }
  }
}

void RunMcapWriter::writePaths(double stamp) {
  const formats::RosTime t = time(stamp);
  writeText(kRunEstimatePathTopic, stamp, estimate_path_.message(t, kPlanFrame));
  writeText(kRunEstimateMapPathTopic, stamp, estimate_map_path_.message(t, kMapFrame));
}

void RunMcapWriter::finish(const Json& final_graph, const slam::DeviationReport* deviations) {
  if (!started_) start(0.0);
  writeSnapshot(last_stamp_, final_graph);
  writePaths(last_stamp_);
  if (agraph_ && deviations) {
    writeJson(kRunDeviationsTopic, last_stamp_,
              fx::sceneUpdate(deviationEntities(*deviations, *agraph_, time(last_stamp_))));
  }
  mcap_.close();
}

std::vector<std::pair<std::string, std::uint64_t>> RunMcapWriter::counts() const {
  std::vector<std::pair<std::string, std::uint64_t>> counts;
  for (const auto& [name, channel] : channels_) {
    counts.emplace_back(name, channel < mcap_.counts().size() ? mcap_.counts()[channel] : 0);
  }
  return counts;
}

bool isRunFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  return fs::is_regular_file(fs::path(dir) / "metrics.json") &&
         fs::is_regular_file(fs::path(dir) / "estimate_map.tum");
}

namespace {

RunExportSummary exportRunFolder(const std::string& run_dir, const std::string& mcap_path,
                                 const RunMcapOptions& options) {
  namespace fs = std::filesystem;
  const fs::path dir(run_dir);
  const auto file = [&](const char* name) { return (dir / name).string(); };
  const auto optionalJson = [&](const char* name) -> std::optional<Json> {
    if (!fs::exists(file(name))) return std::nullopt;
    return common::readJsonFile(file(name));
  };
  const Json metrics = common::readJsonFile(file("metrics.json"));
  const Json graph = common::readJsonFile(file("sgraph.json"));
  const std::optional<Json> agraph = optionalJson("agraph.json");
  const std::optional<slam::DeviationReport> deviations =
      fs::exists(file("deviations.json"))
          ? std::optional<slam::DeviationReport>(loadDeviationReport(file("deviations.json")))
          : std::nullopt;
  const common::Trajectory estimate_map = formats::readTrajectoryFile(file("estimate_map.tum"));
  const common::Trajectory estimate =
      formats::readTrajectoryFile(file("estimate.tum"), /*require_poses=*/false);
  const common::Trajectory ground_truth =
      fs::exists(file("groundtruth.tum"))
          ? formats::readTrajectoryFile(file("groundtruth.tum"), /*require_poses=*/false)
          : common::Trajectory{};
  std::vector<MatchingEvent> events;
  if (const auto it = metrics.find("matching_events"); it != metrics.end() && it->is_array()) {
    for (const Json& e : *it) {
      events.push_back({e.value("stamp", 0.0), e.value("keyframe", 0),
                        e.value("status", std::string()), e.value("reason", std::string())});
    }
  }
  RunMcapOptions without_scans = options;
  without_scans.scans = false;
  RunMcapWriter writer(mcap_path, without_scans, agraph ? &*agraph : nullptr, std::nullopt,
                       ground_truth);

  std::size_t next_estimate = 0, next_event = 0;
  for (const auto& row : estimate_map) {
    RunMoment moment;
    moment.stamp = row.t;
    moment.M_T_R = row.pose;
    // estimate.tum's rows are estimate_map.tum's from the localized one on, at the same stamps.
    while (next_estimate < estimate.size() && estimate[next_estimate].t < row.t - 1e-9) {
      ++next_estimate;
    }
    if (next_estimate < estimate.size() && std::abs(estimate[next_estimate].t - row.t) <= 1e-9) {
      moment.B_T_M = estimate[next_estimate].pose * row.pose.inverse();
    }
    while (next_event < events.size() && events[next_event].stamp <= row.t + 1e-9) {
      moment.events.push_back(events[next_event++]);
    }
    Json snapshot;
    if (writer.snapshotDue(row.t)) {
      snapshot = graphSoFar(graph, row.t);
      moment.graph = &snapshot;
    }
    writer.add(moment);
  }
  if (next_event < events.size()) {  // changes after the last estimate: at its stamp
    RunMoment last;
    last.stamp = estimate_map.empty() ? 0.0 : estimate_map.back().t;
    last.events.assign(events.begin() + long(next_event), events.end());
    writer.add(last);
  }
  writer.finish(graph, deviations ? &*deviations : nullptr);
  return {writer.counts(), estimate_map.empty() ? 0.0 : estimate_map.back().t};
}

}  // namespace

RunExportSummary exportRunMcap(const std::string& run_dir, const std::string& mcap_path,
                               const RunMcapOptions& options) {
  try {
    return exportRunFolder(run_dir, mcap_path, options);
  } catch (const nlohmann::json::exception& e) {
    // A document of the folder without what isg writes in it (edited, or another tool's).
    throw common::InputError(
        run_dir, "",
        std::string("a JSON file of the run folder is not as isg writes it: ") + e.what());
  }
}

}  // namespace isg::run
