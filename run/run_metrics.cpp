#include "run/run_metrics.hpp"

#include <cmath>
#include <filesystem>

#include "bim/input_error.hpp"
#include "bim/json_reader.hpp"

namespace isg::run {

namespace {

nlohmann::json statisticsJson(const Statistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max},   {"sse", s.sse}};
}

// Reads fields of one JSON object, naming the file and the field's pointer when one is wrong.
class FieldReader {
 public:
  FieldReader(const nlohmann::json& object, std::string pointer, const std::string& file)
      : object_(object), pointer_(std::move(pointer)), file_(file) {
    if (!object_.is_object()) fail(pointer_, "expected an object");
  }

  template <typename T>
  T required(const char* key) const {
    if (!object_.contains(key)) fail(pointer_ + "/" + key, "missing");
    return get<T>(key);
  }
  template <typename T>
  std::optional<T> optional(const char* key) const {
    if (!object_.contains(key)) return std::nullopt;
    return get<T>(key);
  }
  std::optional<Statistics> statistics(const char* key) const {
    if (!object_.contains(key)) return std::nullopt;
    const FieldReader s(object_[key], pointer_ + "/" + key, file_);
    // Statistics of errors (metres, degrees): counts and values are never negative.
    Statistics out;
    out.count = s.required<int>("count");
    if (out.count < 0) fail(pointer_ + "/" + key + "/count", "must be >= 0");
    out.rmse = s.measure("rmse");
    out.mean = s.measure("mean");
    out.median = s.measure("median");
    out.std = s.measure("std");
    out.min = s.measure("min");
    out.max = s.measure("max");
    out.sse = s.measure("sse");
    return out;
  }
  // A required number that is finite and >= 0 (a time, a distance, an error).
  double measure(const char* key) const {
    const double value = required<double>(key);
    if (value < 0.0) fail(pointer_ + "/" + key, "must be >= 0, got " + object_[key].dump());
    return value;
  }
  std::optional<double> optionalMeasure(const char* key) const {
    if (!object_.contains(key)) return std::nullopt;
    return measure(key);
  }
  // An optional array of numbers (empty when absent).
  std::vector<double> numbers(const char* key) const {
    std::vector<double> out;
    if (!object_.contains(key)) return out;
    const nlohmann::json& array = object_[key];
    const std::string pointer = pointer_ + "/" + key;
    if (!array.is_array()) fail(pointer, "expected an array of numbers");
    for (std::size_t i = 0; i < array.size(); ++i) {
      if (!array[i].is_number() || !std::isfinite(array[i].get<double>())) {
        fail(pointer + "/" + std::to_string(i), "expected a finite number");
      }
      out.push_back(array[i].get<double>());
    }
    return out;
  }
  const nlohmann::json& object() const { return object_; }
  const std::string& pointer() const { return pointer_; }
  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw bim::InputError(file_, pointer, what);
  }

 private:
  template <typename T>
  T get(const char* key) const {
    const nlohmann::json& value = object_[key];
    const std::string pointer = pointer_ + "/" + key;
    if constexpr (std::is_same_v<T, bool>) {
      if (!value.is_boolean()) fail(pointer, "expected true or false");
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!value.is_string()) fail(pointer, "expected a string");
    } else if constexpr (std::is_integral_v<T>) {
      if (!value.is_number_integer() || (std::is_unsigned_v<T> && value.get<double>() < 0)) {
        fail(pointer, "expected an integer");
      }
    } else {
      if (!value.is_number()) fail(pointer, "expected a number");
      if (!std::isfinite(value.get<double>())) fail(pointer, "expected a finite number");
    }
    return value.get<T>();
  }

  const nlohmann::json& object_;
  std::string pointer_;
  const std::string& file_;
};

bool isContentHash(const std::string& text) {
  const std::string prefix = "sha256:";
  return text.size() == prefix.size() + 64 && text.rfind(prefix, 0) == 0 &&
         text.find_first_not_of("0123456789abcdef", prefix.size()) == std::string::npos;
}

}  // namespace

nlohmann::json metricsToJson(const RunMetrics& m) {
  nlohmann::json j;
  j["world"] = m.world;
  j["method"] = m.method;
  j["seed"] = m.seed;
  if (m.world_hash) j["world_hash"] = *m.world_hash;
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
  if (m.matching_status) {
    j["matching_status"] = *m.matching_status;
    j["lost_at"] = m.lost_at;
    j["relocalized_at"] = m.relocalized_at;
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : m.matching_events) {
      events.push_back({{"stamp", e.stamp},
                        {"keyframe", e.keyframe},
                        {"status", e.status},
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

RunMetrics metricsFromJson(const nlohmann::json& document, const std::string& file) {
  const FieldReader r(document, "", file);
  RunMetrics m;
  m.world = r.required<std::string>("world");
  m.method = r.required<std::string>("method");
  m.seed = r.required<std::uint64_t>("seed");
  m.world_hash = r.optional<std::string>("world_hash");
  if (m.world_hash && !isContentHash(*m.world_hash)) {
    r.fail("/world_hash", "expected \"sha256:\" and 64 hex digits");
  }
  m.scans = r.required<int>("scans");
  if (m.scans < 0) r.fail("/scans", "must be >= 0");
  m.sim_seconds = r.measure("sim_seconds");
  m.wall_seconds = r.measure("wall_seconds");
  m.real_time_factor = r.measure("real_time_factor");
  m.localized = r.required<bool>("localized");
  m.time_to_localize = r.optionalMeasure("time_to_localize");
  m.distance_to_localize = r.optionalMeasure("distance_to_localize");
  m.rooms_visited_to_localize = r.optional<int>("rooms_visited_to_localize");
  if (m.rooms_visited_to_localize && *m.rooms_visited_to_localize < 0) {
    r.fail("/rooms_visited_to_localize", "must be >= 0");
  }
  m.share_localized = r.optionalMeasure("share_localized");
  if (m.share_localized && *m.share_localized > 1.0) r.fail("/share_localized", "must be <= 1");
  m.ape_B = r.statistics("ape_B");
  m.ape_B_rotation_deg = r.statistics("ape_B_rotation_deg");
  m.ape_M_se3 = r.statistics("ape_M_se3");
  m.ape_odometry_from_true_start = r.statistics("ape_odometry_from_true_start");
  m.wrongly_localized = r.optional<bool>("wrongly_localized");
  m.time_wrongly_localized = r.optionalMeasure("time_wrongly_localized");
  m.max_error_B = r.optionalMeasure("max_error_B");
  m.matching_status = r.optional<std::string>("matching_status");
  m.lost_at = r.numbers("lost_at");
  m.relocalized_at = r.numbers("relocalized_at");
  if (document.contains("timing")) {
    const FieldReader t(document["timing"], "/timing", file);
    RunTiming timing;
    timing.scans_read = t.required<int>("scans_read");
    timing.localizer_seconds = t.required<double>("localizer_seconds");
    timing.scan_wait_seconds = t.required<double>("scan_wait_seconds");
    timing.peak_memory_mb = t.optional<double>("peak_memory_mb");
    if (!t.object().contains("stages")) t.fail("/timing/stages", "missing");
    const nlohmann::json& stages = t.object()["stages"];
    if (!stages.is_array()) t.fail("/timing/stages", "expected an array");
    for (std::size_t i = 0; i < stages.size(); ++i) {
      const FieldReader s(stages[i], "/timing/stages/" + std::to_string(i), file);
      timing.stages.push_back({s.required<std::string>("stage"), s.required<double>("seconds")});
    }
    m.timing = timing;
  }
  if (document.contains("matching_events")) {
    const auto& events = document["matching_events"];
    if (!events.is_array()) r.fail("/matching_events", "expected an array");
    for (std::size_t i = 0; i < events.size(); ++i) {
      const FieldReader e(events[i], "/matching_events/" + std::to_string(i), file);
      m.matching_events.push_back({e.required<double>("stamp"), e.required<int>("keyframe"),
                                   e.required<std::string>("status"),
                                   e.required<std::string>("reason")});
    }
  }
  if (document.contains("notes")) {
    const auto& notes = document["notes"];
    if (!notes.is_array()) r.fail("/notes", "expected an array of strings");
    for (std::size_t i = 0; i < notes.size(); ++i) {
      if (!notes[i].is_string()) r.fail("/notes/" + std::to_string(i), "expected a string");
      m.notes.push_back(notes[i].get<std::string>());
    }
  }
  if (m.localized && (!m.time_to_localize || !m.share_localized)) {
    r.fail("/localized", "a localized run needs time_to_localize and share_localized");
  }
  return m;
}

RunMetrics readMetrics(const std::string& run_dir) {
  const std::string path = (std::filesystem::path(run_dir) / kMetricsFile).string();
  if (!std::filesystem::is_regular_file(path)) {
    throw bim::InputError(run_dir, "", "not a run folder (no metrics.json)");
  }
  return metricsFromJson(bim::readJsonFile(path), path);
}

}  // namespace isg::run
