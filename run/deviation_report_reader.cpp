#include "run/deviation_report_reader.hpp"

#include <cmath>

#include "common/angles.hpp"

namespace isg::run {
namespace {

using common::JsonNode;

template <class Status>
Status statusNamed(const JsonNode& node, std::initializer_list<Status> statuses) {
  const std::string name = node.string();
  std::string known;
  for (Status status : statuses) {
    if (name == slam::toString(status)) return status;
    known += (known.empty() ? "" : ", ") + std::string(slam::toString(status));
  }
  node.fail("unknown status " + common::inQuotes(name) + " (expected one of " + known + ")");
}

std::optional<double> optionalNumber(const JsonNode& node) {
  if (node.raw().is_null()) return std::nullopt;
  return node.number();
}

int integer(const JsonNode& node) { return int(node.integer()); }

slam::DeviationOptions readThresholds(const JsonNode& t) {
  slam::DeviationOptions o;
  o.shift_m = t.field("shift_m").number();
  o.angle_deg = t.field("angle_deg").number();
  o.noise_factor = t.field("noise_factor").number();
  o.min_noise_walls = integer(t.field("min_noise_walls"));
  o.min_angle_length = t.field("min_angle_length_m").number();
  o.consistent_tolerance = t.field("consistent_tolerance_m").number();
  o.contradiction_observation_share = t.field("contradiction_observation_share").number();
  o.min_deviation_observations = integer(t.field("min_deviation_observations"));
  o.max_stray_lean_deg = t.field("max_stray_lean_deg").number();
  o.judged_share = t.field("judged_share").number();
  o.missing_seen_share = t.field("missing_seen_share").number();
  o.missing_view_share = t.field("missing_view_share").number();
  o.missing_sight_share = t.field("missing_sight_share").number();
  o.min_missing_length = t.field("min_missing_length_m").number();
  o.search_distance = t.field("search_distance_m").number();
  o.search_angle_deg = t.field("search_angle_deg").number();
  o.min_wall_length = t.field("min_wall_length_m").number();
  o.column_margin = t.field("column_margin_m").number();
  o.bend_distance = t.field("bend_distance_m").number();
  o.bend_angle_deg = t.field("bend_angle_deg").number();
  o.local_radius = t.field("local_radius_m").number();
  o.view_range = t.field("view_range_m").number();
  o.max_incidence_deg = t.field("max_incidence_deg").number();
  o.min_views = integer(t.field("min_views"));
  o.see_through_margin = t.field("see_through_margin_m").number();
  o.window_margin = t.field("window_margin_m").number();
  o.extra_pair_distance = t.field("extra_pair_distance_m").number();
  o.pivot_name_distance = t.field("pivot_name_distance_m").number();
  o.progress_step = t.field("progress_step_m").number();
  // Reports written before verdicts carried their uncertainty have neither: the defaults.
  if (auto v = t.optionalField("end_sigma_m")) o.end_sigma_m = v->number();
  if (auto v = t.optionalField("clear_factor")) o.clear_factor = v->number();
  o.progress_gap_m = t.field("progress_gap_m").number();
  return o;
}

slam::ColumnOptions readColumnThresholds(const JsonNode& c) {
  slam::ColumnOptions o;
  o.search_m = c.field("search_m").number();
  o.band_margin_m = c.field("band_margin_m").number();
  o.wall_clearance_m = c.field("wall_clearance_m").number();
  o.inlier_m = c.field("inlier_m").number();
  o.min_points = std::size_t(c.field("min_points").unsignedInteger());
  o.min_direction_weight = c.field("min_direction_weight").number();
  o.moved_m = c.field("moved_m").number();
  o.view_range_m = c.field("view_range_m").number();
  o.see_past_margin_m = c.field("see_past_margin_m").number();
  o.min_views = integer(c.field("min_views"));
  return o;
}

slam::WallEvidence readEvidence(const JsonNode& e) {
  slam::WallEvidence evidence;
  evidence.plane = integer(e.field("plane"));
  const std::string face = e.field("face").string();
  if (face != "left" && face != "right") e.field("face").fail("expected \"left\" or \"right\"");
  evidence.side = face == "left" ? +1 : -1;
  evidence.length_m = e.field("length_m").number();
  evidence.observations = integer(e.field("observations"));
  evidence.offset_m = e.field("offset_m").number();
  evidence.angle_deg = e.field("angle_deg").number();
  evidence.consistent = e.field("consistent").boolean();
  evidence.start_B = e.field("start").point2();
  evidence.end_B = e.field("end").point2();
  return evidence;
}

slam::WallProgress readProgress(const JsonNode& p) {
  using slam::ProgressStatus;
  slam::WallProgress progress;
  progress.status =
      statusNamed(p.field("status"), {ProgressStatus::kBuilt, ProgressStatus::kPartlyBuilt,
                                      ProgressStatus::kNotBuilt, ProgressStatus::kNotSeen});
  progress.planned_m = p.field("planned_m").number();
  progress.built_m = p.field("built_m").number();
  progress.not_built_m = p.field("not_built_m").number();
  progress.not_seen_m = p.field("not_seen_m").number();
  for (const JsonNode& span : p.field("built").elements()) {
    const Eigen::Vector2d ab = span.point2();
    progress.built.push_back({ab.x(), ab.y()});
  }
  return progress;
}

slam::WallDeviation readWall(const JsonNode& w) {
  using slam::WallStatus;
  slam::WallDeviation wall;
  wall.wall = w.field("wall").string();
  wall.level = w.field("level").string();
  wall.status = statusNamed(w.field("status"),
                            {WallStatus::kAsPlanned, WallStatus::kShifted, WallStatus::kRotated,
                             WallStatus::kMissing, WallStatus::kNotSeen});
  wall.offset_m = optionalNumber(w.field("offset_m"));
  wall.angle_deg = optionalNumber(w.field("angle_deg"));
  if (auto v = w.optionalField("offset_sigma_m")) wall.offset_sigma_m = optionalNumber(*v);
  if (auto v = w.optionalField("angle_sigma_deg")) wall.angle_sigma_deg = optionalNumber(*v);
  wall.observed_share = w.field("observed_share").number();
  wall.planned_start = w.field("planned").field("start").point2();
  wall.planned_end = w.field("planned").field("end").point2();
  for (const JsonNode& e : w.field("evidence").elements()) wall.evidence.push_back(readEvidence(e));
  if (auto share = w.optionalField("in_view_share")) wall.in_view_share = share->number();
  if (auto guid = w.optionalField("ifc_guid")) wall.ifc_guid = guid->string();
  if (auto judged = w.optionalField("judged_against")) {
    wall.shift_threshold_m = judged->field("shift_m").number();
    wall.angle_threshold_deg = judged->field("angle_deg").number();
    wall.local_offset_noise_m = optionalNumber(judged->field("local_offset_noise_m"));
    wall.local_angle_noise_deg = optionalNumber(judged->field("local_angle_noise_deg"));
    wall.placement_sigma_m = judged->field("placement_sigma_m").number();
    if (auto v = judged->optionalField("placement_angle_sigma_deg")) {
      wall.placement_angle_sigma_deg = v->number();
    }
  }
  wall.progress = readProgress(w.field("progress"));
  if (auto turned = w.optionalField("turned_about")) {
    wall.pivot_along_m = turned->field("along_m").number();
    if (auto v = turned->optionalField("sigma_m")) wall.pivot_sigma_m = optionalNumber(*v);
    wall.turned_about = turned->field("name").string();
  }
  return wall;
}

slam::ColumnDeviation readColumn(const JsonNode& c) {
  using slam::ColumnStatus;
  slam::ColumnDeviation column;
  column.column = c.field("column").string();
  column.level = c.field("level").string();
  const std::string shape = c.field("shape").string();
  if (shape != "round" && shape != "rectangle") {
    c.field("shape").fail("expected \"round\" or \"rectangle\"");
  }
  column.round = shape == "round";
  column.status = statusNamed(c.field("status"), {ColumnStatus::kAsPlanned, ColumnStatus::kMoved,
                                                  ColumnStatus::kMissing, ColumnStatus::kNotSeen});
  column.planned_centre = c.field("planned_centre").point2();
  column.points = std::size_t(c.field("points").unsignedInteger());
  if (!c.field("offset_m").raw().is_null()) column.offset_m = c.field("offset_m").point2();
  column.directions_measured = integer(c.field("directions_measured"));
  column.seen_past = integer(c.field("seen_past"));
  if (auto guid = c.optionalField("ifc_guid")) column.ifc_guid = guid->string();
  return column;
}

slam::LevelAgainstPlan readAgainstPlan(const JsonNode& l) {
  slam::LevelAgainstPlan level;
  level.level = l.field("level").string();
  level.points = std::size_t(l.field("points").unsignedInteger());
  level.near_share = l.field("near_share").number();
  level.cutoff_m = l.field("cutoff_m").number();
  level.median_m = l.field("median_m").number();
  level.p95_m = l.field("p95_m").number();
  for (const JsonNode& s : l.field("stretches").elements()) {
    slam::FaceStretch stretch;
    stretch.surface = s.field("surface").string();
    stretch.start = s.field("start").point2();
    stretch.end = s.field("end").point2();
    stretch.points = std::size_t(s.field("points").unsignedInteger());
    stretch.mean_m = s.field("mean_m").number();
    stretch.rms_m = s.field("rms_m").number();
    level.stretches.push_back(stretch);
  }
  return level;
}

}  // namespace

slam::DeviationReport readDeviationReport(const JsonNode& root) {
  common::checkFormatAndVersion(root, "isg.deviations", 1);
  if (root.field("frame").string() != "B") root.field("frame").fail("expected \"B\"");
  slam::DeviationReport report;
  const JsonNode thresholds = root.field("thresholds");
  report.options = readThresholds(thresholds);
  for (const JsonNode& level : root.field("levels").elements()) {
    report.levels.push_back(level.string());
  }
  for (const JsonNode& p : root.field("placement_correction").elements()) {
    slam::PlacementCorrection placement;
    placement.level = p.field("level").string();
    placement.correction = {p.field("x").number(), p.field("y").number(),
                            common::radians(p.field("yaw_deg").number())};
    placement.walls_used = integer(p.field("walls_used"));
    report.placements.push_back(placement);
  }
  for (const JsonNode& w : root.field("walls").elements()) report.walls.push_back(readWall(w));
  for (const JsonNode& e : root.field("extra_walls").elements()) {
    slam::ExtraWall extra;
    extra.level = e.field("level").string();
    extra.start = e.field("start").point2();
    extra.end = e.field("end").point2();
    for (const JsonNode& plane : e.field("planes").elements()) {
      extra.planes.push_back(integer(plane));
    }
    report.extra_walls.push_back(extra);
  }
  if (auto columns = root.optionalField("columns")) {
    for (const JsonNode& c : columns->elements()) report.columns.push_back(readColumn(c));
    report.column_options = readColumnThresholds(thresholds.field("columns"));
  }
  if (auto levels = root.optionalField("map_against_plan")) {
    for (const JsonNode& l : levels->elements()) {
      report.against_plan.push_back(readAgainstPlan(l));
    }
  }
  return report;
}

slam::DeviationReport loadDeviationReport(const std::string& path) {
  const nlohmann::json document =
      common::parseJsonText(common::readCheckedFile(path, 256ull << 20), path);
  const common::JsonSource source{path, nullptr};
  return readDeviationReport(common::JsonNode(document, "", source));
}

}  // namespace isg::run
