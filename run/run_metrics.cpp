#include "run/run_metrics.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <string_view>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "run/estimate_states.hpp"

namespace isg::run {

namespace {

nlohmann::json statisticsJson(const Statistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max},   {"sse", s.sse}};
}

// metrics.json's fields read through common::JsonNode, which names the file and the field's pointer
// when one is missing or wrong. Every measure is finite and >= 0 (a time, a distance, an error).
int countOf(const common::JsonNode& node) {
  const std::int64_t value = node.integer();
  if (value < 0) node.fail("must be >= 0, got " + std::to_string(value));
  if (value > std::numeric_limits<int>::max()) node.fail("too large: " + std::to_string(value));
  return int(value);
}

std::optional<double> optionalMeasure(const common::JsonNode& object, std::string_view key) {
  if (const auto field = object.optionalField(key)) return field->nonNegativeNumber();
  return std::nullopt;
}

std::optional<Statistics> optionalStatistics(const common::JsonNode& object, std::string_view key) {
  const auto field = object.optionalField(key);
  if (!field) return std::nullopt;
  Statistics out;
  out.count = countOf(field->field("count"));
  out.rmse = field->field("rmse").nonNegativeNumber();
  out.mean = field->field("mean").nonNegativeNumber();
  out.median = field->field("median").nonNegativeNumber();
  out.std = field->field("std").nonNegativeNumber();
  out.min = field->field("min").nonNegativeNumber();
  out.max = field->field("max").nonNegativeNumber();
  out.sse = field->field("sse").nonNegativeNumber();
  return out;
}

// An optional array of finite numbers (empty when absent).
std::vector<double> optionalNumbers(const common::JsonNode& object, std::string_view key) {
  std::vector<double> out;
  if (const auto field = object.optionalField(key)) {
    for (const auto& element : field->elements()) out.push_back(element.number());
  }
  return out;
}

nlohmann::json mapToPlanLevelJson(const RunMetrics::MapToPlan::Level& level) {
  nlohmann::json out = {{"level", level.level},
                        {"points", level.points},
                        {"near_share", level.near_share},
                        {"median_m", level.median_m},
                        {"p95_m", level.p95_m},
                        {"stretches", level.stretches},
                        {"off_stretches", level.off_stretches},
                        {"off_length_m", level.off_length_m}};
  if (level.farthest) {
    const auto& f = *level.farthest;
    out["farthest"] = {{"surface", f.surface},
                       {"mean_m", f.mean_m},
                       {"start", {f.start.x(), f.start.y()}},
                       {"end", {f.end.x(), f.end.y()}}};
  }
  return out;
}

bool isContentHash(const std::string& text) {
  const std::string prefix = "sha256:";
  return text.size() == prefix.size() + 64 && text.rfind(prefix, 0) == 0 &&
         text.find_first_not_of("0123456789abcdef", prefix.size()) == std::string::npos;
}

nlohmann::json estimateStatesJson(const RunMetrics::EstimateStates& e) {
  nlohmann::json states = nlohmann::json::array();
  for (const auto& s : e.states) {
    nlohmann::json one = {{"state", s.state}, {"poses", s.poses}, {"max_sigma_xy", s.max_sigma_xy}};
    if (s.ape_B) one["ape_B"] = statisticsJson(*s.ape_B);
    states.push_back(one);
  }
  return {{"coverage", e.coverage},
          {"coverage_from_first", e.coverage_from_first},
          {"states", states},
          {"keyframes_left_out", e.keyframes_left_out}};
}

}  // namespace

nlohmann::json metricsToJson(const RunMetrics& m) {
  nlohmann::json j;
  j["world"] = m.world;
  j["method"] = m.method;
  j["seed"] = m.seed;
  if (m.world_hash) j["world_hash"] = *m.world_hash;
  if (m.lidar_model) j["lidar_model"] = *m.lidar_model;
  if (m.method_options) {
    j["method_options"] = nlohmann::json::object();
    for (const auto& [key, value] : *m.method_options) j["method_options"][key] = value;
  }
  if (m.build_version) j["build_version"] = *m.build_version;
  j["scans"] = m.scans;
  j["sim_seconds"] = m.sim_seconds;
  j["wall_seconds"] = m.wall_seconds;
  j["real_time_factor"] = m.real_time_factor;
  j["localized"] = m.localized;
  if (m.time_to_localize) j["time_to_localize"] = *m.time_to_localize;
  if (m.distance_to_localize) j["distance_to_localize"] = *m.distance_to_localize;
  if (m.rooms_visited_to_localize) j["rooms_visited_to_localize"] = *m.rooms_visited_to_localize;
  if (m.share_localized) j["share_localized"] = *m.share_localized;
  if (m.ape_B) j["ape_B"] = statisticsJson(*m.ape_B);
  if (m.ape_B_rotation_deg) j["ape_B_rotation_deg"] = statisticsJson(*m.ape_B_rotation_deg);
  if (m.ape_M_se3) j["ape_M_se3"] = statisticsJson(*m.ape_M_se3);
  if (m.ape_odometry_from_true_start) {
    j["ape_odometry_from_true_start"] = statisticsJson(*m.ape_odometry_from_true_start);
  }
  if (m.wrongly_localized) j["wrongly_localized"] = *m.wrongly_localized;
  if (m.time_wrongly_localized) j["time_wrongly_localized"] = *m.time_wrongly_localized;
  if (m.max_error_B) j["max_error_B"] = *m.max_error_B;
  if (m.max_height_error_B) j["max_height_error_B"] = *m.max_height_error_B;
  if (m.floor_plan_score) {
    j["floor_plan_score"] = {{"score", m.floor_plan_score->score},
                             {"coverage", m.floor_plan_score->coverage},
                             {"poses", m.floor_plan_score->poses}};
  }
  if (m.estimate_states) j["estimate_states"] = estimateStatesJson(*m.estimate_states);
  if (m.map_to_plan) {
    nlohmann::json map = statisticsJson(m.map_to_plan->distance);
    map["points"] = m.map_to_plan->points;
    map["near_share"] = m.map_to_plan->near_share;
    map["cutoff_m"] = m.map_to_plan->cutoff;
    if (!m.map_to_plan->levels.empty()) {
      nlohmann::json levels = nlohmann::json::array();
      for (const auto& level : m.map_to_plan->levels) levels.push_back(mapToPlanLevelJson(level));
      map["levels"] = levels;
    }
    j["map_to_plan"] = map;
  }
  if (m.deviations) j["deviations"] = deviationMetricsJson(*m.deviations);
  if (!m.levels.empty()) {
    nlohmann::json levels = nlohmann::json::array();
    for (const LevelMetrics& level : m.levels) {
      nlohmann::json l = {
          {"level", level.level}, {"seconds", level.seconds}, {"arrived_at", level.arrived_at}};
      if (level.first_estimate_at) l["first_estimate_at"] = *level.first_estimate_at;
      if (level.ape_B) l["ape_B"] = statisticsJson(*level.ape_B);
      levels.push_back(l);
    }
    j["levels"] = levels;
  }
  if (m.matching_status) {
    j["matching_status"] = *m.matching_status;
    j["lost_at"] = m.lost_at;
    j["relocalized_at"] = m.relocalized_at;
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : m.matching_events) {
      events.push_back({{"stamp", e.stamp},
                        {"keyframe", e.keyframe},
                        {"status", slam::toString(e.status)},
                        {"reason", e.reason}});
    }
    j["matching_events"] = events;
  }
  if (m.timing) {
    nlohmann::json stages = nlohmann::json::array();
    for (const auto& s : m.timing->stages) {
      stages.push_back(
          {{"stage", s.stage},
           {"seconds", s.seconds},
           {"ms_per_robot_second", m.sim_seconds > 0 ? 1e3 * s.seconds / m.sim_seconds : 0.0}});
    }
    nlohmann::json t = {{"stages", stages},
                        {"scans_read", m.timing->scans_read},
                        {"localizer_seconds", m.timing->localizer_seconds},
                        {"scan_wait_seconds", m.timing->scan_wait_seconds}};
    if (m.timing->peak_memory_mb) t["peak_memory_mb"] = *m.timing->peak_memory_mb;
    j["timing"] = t;
  }
  if (!m.notes.empty()) j["notes"] = m.notes;
  return j;
}

namespace {

std::map<std::string, double> methodOptionsFrom(const common::JsonNode& options) {
  if (!options.isObject()) options.fail("expected an object: option → value");
  std::map<std::string, double> out;
  for (const auto& [key, value] : options.raw().items()) out[key] = options.field(key).number();
  return out;
}

RunMetrics::MapToPlan::Level mapToPlanLevelFrom(const common::JsonNode& l) {
  RunMetrics::MapToPlan::Level level;
  level.level = l.field("level").string();
  level.points = l.field("points").integer();
  if (level.points < 0) l.field("points").fail("must be >= 0");
  level.near_share = l.field("near_share").numberInRange(0.0, 1.0);
  level.median_m = l.field("median_m").nonNegativeNumber();
  level.p95_m = l.field("p95_m").nonNegativeNumber();
  level.stretches = countOf(l.field("stretches"));
  level.off_stretches = countOf(l.field("off_stretches"));
  if (level.off_stretches > level.stretches) {
    l.field("off_stretches").fail("must be at most stretches");
  }
  level.off_length_m = l.field("off_length_m").nonNegativeNumber();
  if (const auto farthest = l.optionalField("farthest")) {
    RunMetrics::MapToPlan::Level::Farthest out;
    out.surface = farthest->field("surface").string();
    out.mean_m = farthest->field("mean_m").number();
    out.start = farthest->field("start").point2();
    out.end = farthest->field("end").point2();
    level.farthest = out;
  }
  return level;
}

RunMetrics::MapToPlan mapToPlanFrom(const common::JsonNode& map, const eval::Statistics& distance) {
  RunMetrics::MapToPlan out;
  out.distance = distance;
  out.points = map.field("points").integer();
  if (out.points < 0) map.field("points").fail("must be >= 0");
  out.near_share = map.field("near_share").numberInRange(0.0, 1.0);
  out.cutoff = map.field("cutoff_m").nonNegativeNumber();
  if (const auto levels = map.optionalField("levels")) {
    for (const auto& l : levels->elements()) out.levels.push_back(mapToPlanLevelFrom(l));
  }
  return out;
}

LevelMetrics levelFrom(const common::JsonNode& l) {
  LevelMetrics level;
  level.level = l.field("level").string();
  level.seconds = l.field("seconds").nonNegativeNumber();
  level.arrived_at = l.field("arrived_at").nonNegativeNumber();
  level.first_estimate_at = optionalMeasure(l, "first_estimate_at");
  level.ape_B = optionalStatistics(l, "ape_B");
  return level;
}

RunTiming timingFrom(const common::JsonNode& t) {
  RunTiming timing;
  timing.scans_read = countOf(t.field("scans_read"));
  timing.localizer_seconds = t.field("localizer_seconds").number();
  timing.scan_wait_seconds = t.field("scan_wait_seconds").number();
  if (const auto peak = t.optionalField("peak_memory_mb")) timing.peak_memory_mb = peak->number();
  for (const auto& stage : t.field("stages").elements()) {
    timing.stages.push_back({stage.field("stage").string(), stage.field("seconds").number()});
  }
  return timing;
}

slam::StatusChange statusChangeFrom(const common::JsonNode& e) {
  const double stamp = e.field("stamp").number();
  const std::int64_t keyframe = e.field("keyframe").integer();
  const common::JsonNode status_node = e.field("status");
  const std::string word = status_node.string();
  const auto status = slam::matchStatusFromString(word);
  if (!status) {
    status_node.fail("unknown status \"" + word +
                     "\" (one of \"not yet\", \"ambiguous\", \"matched\", \"contradicted\", "
                     "\"lost\")");
  }
  if (keyframe < -1 || keyframe > std::numeric_limits<int>::max()) {
    e.field("keyframe").fail("out of range: " + std::to_string(keyframe));
  }
  return {stamp, int(keyframe), *status, e.field("reason").string()};
}

// The run's identity, its length and when it localized.
void identityFrom(const common::JsonNode& root, RunMetrics& m) {
  m.world = root.field("world").string();
  m.method = root.field("method").string();
  m.seed = root.field("seed").unsignedInteger();
  if (const auto hash = root.optionalField("world_hash")) {
    m.world_hash = hash->string();
    if (!isContentHash(*m.world_hash)) hash->fail("expected \"sha256:\" and 64 hex digits");
  }
  if (const auto model = root.optionalField("lidar_model")) m.lidar_model = model->identifier();
  if (const auto options = root.optionalField("method_options")) {
    m.method_options = methodOptionsFrom(*options);
  }
  if (const auto build = root.optionalField("build_version")) m.build_version = build->text();
  m.scans = countOf(root.field("scans"));
  m.sim_seconds = root.field("sim_seconds").nonNegativeNumber();
  m.wall_seconds = root.field("wall_seconds").nonNegativeNumber();
  m.real_time_factor = root.field("real_time_factor").nonNegativeNumber();
  m.localized = root.field("localized").boolean();
  m.time_to_localize = optionalMeasure(root, "time_to_localize");
  m.distance_to_localize = optionalMeasure(root, "distance_to_localize");
  if (const auto rooms = root.optionalField("rooms_visited_to_localize")) {
    m.rooms_visited_to_localize = countOf(*rooms);
  }
  if (const auto share = root.optionalField("share_localized")) {
    m.share_localized = share->numberInRange(0.0, 1.0);
  }
}

}  // namespace

RunMetrics metricsFromJson(const nlohmann::json& document, const std::string& file) {
  const common::JsonSource source{file, nullptr};
  const common::JsonNode root(document, "", source);
  RunMetrics m;
  identityFrom(root, m);
  m.ape_B = optionalStatistics(root, "ape_B");
  m.ape_B_rotation_deg = optionalStatistics(root, "ape_B_rotation_deg");
  m.ape_M_se3 = optionalStatistics(root, "ape_M_se3");
  m.ape_odometry_from_true_start = optionalStatistics(root, "ape_odometry_from_true_start");
  if (const auto wrong = root.optionalField("wrongly_localized")) {
    m.wrongly_localized = wrong->boolean();
  }
  m.time_wrongly_localized = optionalMeasure(root, "time_wrongly_localized");
  m.max_error_B = optionalMeasure(root, "max_error_B");
  m.max_height_error_B = optionalMeasure(root, "max_height_error_B");
  if (const auto score = root.optionalField("floor_plan_score")) {
    eval::FloorPlanScore& out = m.floor_plan_score.emplace();
    out.score = score->field("score").numberInRange(0.0, 100.0);
    out.coverage = score->field("coverage").numberInRange(0.0, 1.0);
    out.poses = countOf(score->field("poses"));
  }
  if (const auto states = root.optionalField("estimate_states")) {
    // Assigned, not emplace()d: clang 14 does not see the nested struct as default-constructible.
    m.estimate_states = RunMetrics::EstimateStates{};
    RunMetrics::EstimateStates& out = *m.estimate_states;
    out.coverage = states->field("coverage").numberInRange(0.0, 1.0);
    out.coverage_from_first = states->field("coverage_from_first").numberInRange(0.0, 1.0);
    for (const auto& s : states->field("states").elements()) {
      out.states.push_back(RunMetrics::EstimateStates::State{});
      RunMetrics::EstimateStates::State& state = out.states.back();
      state.state = s.field("state").string();
      if (!poseStateFromString(state.state)) {
        s.field("state").fail("unknown state \"" + state.state +
                              "\" (one of \"localized\", \"tracking\", \"lost\")");
      }
      state.poses = countOf(s.field("poses"));
      state.ape_B = optionalStatistics(s, "ape_B");
      state.max_sigma_xy = s.field("max_sigma_xy").nonNegativeNumber();
    }
    out.keyframes_left_out = countOf(states->field("keyframes_left_out"));
  }
  if (const auto distance = optionalStatistics(root, "map_to_plan")) {
    m.map_to_plan = mapToPlanFrom(root.field("map_to_plan"), *distance);
  }
  if (const auto deviations = root.optionalField("deviations")) {
    m.deviations = deviationMetricsFromJson(*deviations);
  }
  if (const auto status = root.optionalField("matching_status")) {
    m.matching_status = status->string();
  }
  m.lost_at = optionalNumbers(root, "lost_at");
  m.relocalized_at = optionalNumbers(root, "relocalized_at");
  if (const auto levels = root.optionalField("levels")) {
    for (const auto& l : levels->elements()) m.levels.push_back(levelFrom(l));
  }
  if (const auto t = root.optionalField("timing")) m.timing = timingFrom(*t);
  if (const auto events = root.optionalField("matching_events")) {
    for (const auto& e : events->elements()) m.matching_events.push_back(statusChangeFrom(e));
  }
  if (const auto notes = root.optionalField("notes")) {
    for (const auto& note : notes->elements()) m.notes.push_back(note.string());
  }
  if (m.localized && (!m.time_to_localize || !m.share_localized)) {
    root.field("localized").fail("a localized run needs time_to_localize and share_localized");
  }
  return m;
}

RunMetrics readMetrics(const std::string& run_dir) {
  const std::string path = (std::filesystem::path(run_dir) / kMetricsFile).string();
  if (!std::filesystem::is_regular_file(path)) {
    throw common::InputError(run_dir, "", "not a run folder (no metrics.json)");
  }
  return metricsFromJson(common::readJsonFile(path), path);
}

}  // namespace isg::run
