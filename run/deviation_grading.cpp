#include "run/deviation_grading.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bim/as_built_wall.hpp"
#include "bim/polygon.hpp"

namespace isg::run {

namespace {

std::optional<double> share(int part, int whole) {
  return whole > 0 ? std::optional<double>(double(part) / whole) : std::nullopt;
}

bool onClutter(const Eigen::Vector2d& p, const bim::Clutter& box) {
  const Eigen::Rotation2Dd to_box(-box.yaw);
  const Eigen::Vector2d local = to_box * (p - box.center.head<2>());
  return std::abs(local.x()) <= 0.5 * box.size.x() + 0.3 &&
         std::abs(local.y()) <= 0.5 * box.size.y() + 0.3;
}

}  // namespace

DeviationGrade gradeDeviations(const slam::DeviationReport& report, const bim::Plan& plan,
                               const bim::AsBuilt& truth) {
  DeviationGrade grade;
  double offset_error = 0.0, angle_error = 0.0;
  int measured = 0;
  for (const slam::WallDeviation& wall : report.walls) {
    const bim::Level* level = plan.levelOfWall(wall.wall);
    const bim::Wall* planned = level != nullptr ? level->findWall(wall.wall) : nullptr;
    if (planned == nullptr) continue;
    const bool truly_missing = std::find(truth.missing_walls.begin(), truth.missing_walls.end(),
                                         wall.wall) != truth.missing_walls.end();
    const bool reported_missing = wall.status == slam::WallStatus::kMissing;
    grade.missing_found += truly_missing && reported_missing;
    grade.missing_false_reports += !truly_missing && reported_missing;
    grade.missing_missed += truly_missing && !reported_missing;
    if (truly_missing || wall.observed_share < grade.min_share || !wall.offset_m) continue;
    const bim::Wall built = bim::builtWall(*planned, truth);
    const bim::AxisDeviation true_deviation =
        bim::axisDeviation(*planned, built.start, built.end - built.start);
    const bool truly_deviating = std::abs(true_deviation.offset_m) >= report.options.shift_m ||
                                 std::abs(true_deviation.angle_deg) >= report.options.angle_deg;
    const bool reported =
        wall.status == slam::WallStatus::kShifted || wall.status == slam::WallStatus::kRotated;
    ++grade.judged;
    grade.found += truly_deviating && reported;
    grade.false_reports += !truly_deviating && reported;
    grade.missed += truly_deviating && !reported;
    if (truly_deviating) {
      offset_error += std::abs(*wall.offset_m - true_deviation.offset_m);
      angle_error += std::abs(*wall.angle_deg - true_deviation.angle_deg);
      ++measured;
    }
  }
  grade.precision = share(grade.found, grade.found + grade.false_reports);
  grade.recall = share(grade.found, grade.found + grade.missed);
  if (measured > 0) {
    grade.offset_error_m = offset_error / measured;
    grade.angle_error_deg = angle_error / measured;
  }
  // Extra walls of the levels walked.
  const double parallel = std::cos(10.0 * std::numbers::pi / 180.0);
  std::vector<bool> matched(truth.extra_walls.size(), false);
  for (const slam::ExtraWall& extra : report.extra_walls) {
    const Eigen::Vector2d middle = 0.5 * (extra.start + extra.end);
    const Eigen::Vector2d direction = (extra.end - extra.start).normalized();
    bool any = false;
    for (std::size_t t = 0; t < truth.extra_walls.size(); ++t) {
      const bim::ExtraWall& wall = truth.extra_walls[t];
      if (wall.level != extra.level) continue;
      const Eigen::Vector2d axis = (wall.end - wall.start).normalized();
      if (std::abs(axis.dot(direction)) < parallel) continue;
      if (bim::distanceToSegment(middle, wall.start, wall.end) > 0.3) continue;
      matched[t] = true;
      any = true;
    }
    if (any) {
      ++grade.extra_found;
    } else if (std::any_of(truth.clutter.begin(), truth.clutter.end(), [&](const auto& box) {
                 return box.level == extra.level && onClutter(middle, box);
               })) {
      ++grade.extra_on_clutter;
    } else {
      ++grade.extra_false_reports;
    }
  }
  int true_extra = 0, true_found = 0;
  for (std::size_t t = 0; t < truth.extra_walls.size(); ++t) {
    if (std::find(report.levels.begin(), report.levels.end(), truth.extra_walls[t].level) ==
        report.levels.end()) {
      continue;
    }
    ++true_extra;
    true_found += matched[t];
  }
  grade.extra_missed = true_extra - true_found;
  grade.extra_precision = share(grade.extra_found, grade.extra_found + grade.extra_false_reports);
  grade.extra_recall = share(true_found, true_extra);
  return grade;
}

DeviationMetrics deviationMetrics(const slam::DeviationReport& report, const bim::Plan* plan,
                                  const bim::AsBuilt* truth) {
  DeviationMetrics m;
  m.as_planned = report.count(slam::WallStatus::kAsPlanned);
  m.shifted = report.count(slam::WallStatus::kShifted);
  m.rotated = report.count(slam::WallStatus::kRotated);
  m.missing = report.count(slam::WallStatus::kMissing);
  m.not_seen = report.count(slam::WallStatus::kNotSeen);
  m.extra_walls = int(report.extra_walls.size());
  if (plan != nullptr && truth != nullptr) m.grade = gradeDeviations(report, *plan, *truth);
  return m;
}

namespace {

void putOptional(nlohmann::json& j, const char* key, const std::optional<double>& value) {
  if (value) j[key] = *value;
}

std::optional<double> readShare(const bim::JsonNode& node, std::string_view key) {
  if (const auto field = node.optionalField(key)) return field->numberInRange(0.0, 1.0);
  return std::nullopt;
}

std::optional<double> readMeasure(const bim::JsonNode& node, std::string_view key) {
  if (const auto field = node.optionalField(key)) return field->nonNegativeNumber();
  return std::nullopt;
}

int readCount(const bim::JsonNode& node, std::string_view key) {
  const bim::JsonNode field = node.field(key);
  const std::int64_t value = field.integer();
  if (value < 0 || value > 1000000000) field.fail("must be a count, got " + std::to_string(value));
  return int(value);
}

}  // namespace

nlohmann::json deviationMetricsJson(const DeviationMetrics& m) {
  nlohmann::json j = {{"walls",
                       {{"as_planned", m.as_planned},
                        {"shifted", m.shifted},
                        {"rotated", m.rotated},
                        {"missing", m.missing},
                        {"not_seen", m.not_seen}}},
                      {"extra_walls", m.extra_walls}};
  if (m.grade) {
    const DeviationGrade& g = *m.grade;
    nlohmann::json graded = {{"min_share", g.min_share},
                             {"judged", g.judged},
                             {"found", g.found},
                             {"false_reports", g.false_reports},
                             {"missed", g.missed}};
    putOptional(graded, "precision", g.precision);
    putOptional(graded, "recall", g.recall);
    putOptional(graded, "offset_error_m", g.offset_error_m);
    putOptional(graded, "angle_error_deg", g.angle_error_deg);
    graded["missing"] = {{"found", g.missing_found},
                         {"false_reports", g.missing_false_reports},
                         {"missed", g.missing_missed}};
    nlohmann::json extra = {{"found", g.extra_found},
                            {"false_reports", g.extra_false_reports},
                            {"missed", g.extra_missed},
                            {"on_clutter", g.extra_on_clutter}};
    putOptional(extra, "precision", g.extra_precision);
    putOptional(extra, "recall", g.extra_recall);
    graded["extra"] = extra;
    j["graded"] = graded;
  }
  return j;
}

DeviationMetrics deviationMetricsFromJson(const bim::JsonNode& node) {
  DeviationMetrics m;
  const bim::JsonNode walls = node.field("walls");
  m.as_planned = readCount(walls, "as_planned");
  m.shifted = readCount(walls, "shifted");
  m.rotated = readCount(walls, "rotated");
  m.missing = readCount(walls, "missing");
  m.not_seen = readCount(walls, "not_seen");
  m.extra_walls = readCount(node, "extra_walls");
  if (const auto graded = node.optionalField("graded")) {
    DeviationGrade g;
    g.min_share = graded->field("min_share").numberInRange(0.0, 1.0);
    g.judged = readCount(*graded, "judged");
    g.found = readCount(*graded, "found");
    g.false_reports = readCount(*graded, "false_reports");
    g.missed = readCount(*graded, "missed");
    g.precision = readShare(*graded, "precision");
    g.recall = readShare(*graded, "recall");
    g.offset_error_m = readMeasure(*graded, "offset_error_m");
    g.angle_error_deg = readMeasure(*graded, "angle_error_deg");
    const bim::JsonNode missing = graded->field("missing");
    g.missing_found = readCount(missing, "found");
    g.missing_false_reports = readCount(missing, "false_reports");
    g.missing_missed = readCount(missing, "missed");
    const bim::JsonNode extra = graded->field("extra");
    g.extra_found = readCount(extra, "found");
    g.extra_false_reports = readCount(extra, "false_reports");
    g.extra_missed = readCount(extra, "missed");
    g.extra_on_clutter = readCount(extra, "on_clutter");
    g.extra_precision = readShare(extra, "precision");
    g.extra_recall = readShare(extra, "recall");
    m.grade = g;
  }
  return m;
}

}  // namespace isg::run
