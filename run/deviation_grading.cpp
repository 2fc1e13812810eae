#include "run/deviation_grading.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bim/as_built_wall.hpp"
#include "bim/polygon.hpp"
#include "common/angles.hpp"

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

// Built-length errors summed: over the walls found partly built, and over those seen end to end.
struct LengthErrors {
  double all = 0.0, seen = 0.0;
  int measured = 0, measured_seen = 0;
};

// A wall's progress against the truth (DeviationGrade, "Progress"): judged when built or not
// built was seen over min_share of its exposed length. A missing wall is graded as missing.
void gradeProgress(const slam::WallProgress& progress, const bim::ShortenedWall* shortened,
                   bool truly_missing, DeviationGrade& grade, LengthErrors& errors) {
  if (truly_missing || progress.planned_m <= 0.0) return;
  if (progress.built_m + progress.not_built_m < grade.min_share * progress.planned_m) return;
  const bool reported = progress.status == slam::ProgressStatus::kPartlyBuilt ||
                        progress.status == slam::ProgressStatus::kNotBuilt;
  grade.partly_found += shortened != nullptr && reported;
  grade.partly_false_reports += shortened == nullptr && reported;
  grade.partly_missed += shortened != nullptr && !reported;
  if (shortened != nullptr && progress.status == slam::ProgressStatus::kPartlyBuilt) {
    const double truly_built = slam::overlapLength(progress.exposed, shortened->built);
    const double error = std::abs(progress.built_m - truly_built);
    errors.all += error;
    ++errors.measured;
    if (progress.not_seen_m < DeviationGrade::kSeenEndToEnd) {
      errors.seen += error;
      ++errors.measured_seen;
    }
  }
}

// The columns against the truth (DeviationGrade, "Columns").
void gradeColumns(const slam::DeviationReport& report, const bim::AsBuilt& truth,
                  DeviationGrade& grade) {
  const double moved_m = report.column_options.moved_m;
  double offset_error = 0.0;
  int offsets = 0;
  for (const slam::ColumnDeviation& column : report.columns) {
    if (column.status == slam::ColumnStatus::kNotSeen) continue;
    const bool truly_missing = std::find(truth.missing_columns.begin(), truth.missing_columns.end(),
                                         column.column) != truth.missing_columns.end();
    const auto move =
        std::find_if(truth.moved_columns.begin(), truth.moved_columns.end(),
                     [&](const bim::ColumnMove& m) { return m.column == column.column; });
    const bool truly_moved = move != truth.moved_columns.end() && move->offset.norm() >= moved_m;
    const bool reported = column.status == slam::ColumnStatus::kMissing ||
                          column.status == slam::ColumnStatus::kMoved;
    if (truly_missing || truly_moved) {
      const bool right = truly_missing ? column.status == slam::ColumnStatus::kMissing
                                       : column.status == slam::ColumnStatus::kMoved;
      ++(right ? grade.column_found : grade.column_missed);
      if (right && truly_moved && column.offset_m) {
        offset_error += (*column.offset_m - move->offset).norm();
        ++offsets;
      }
    } else if (reported) {
      ++grade.column_false_reports;
    }
  }
  grade.column_precision =
      share(grade.column_found, grade.column_found + grade.column_false_reports);
  grade.column_recall = share(grade.column_found, grade.column_found + grade.column_missed);
  if (offsets > 0) grade.column_offset_error_m = offset_error / offsets;
}

}  // namespace

namespace {

// Sums over the walls graded for what deviates, to be turned into means.
struct DeviationSums {
  double offset_error = 0.0, angle_error = 0.0, pivot_error = 0.0;
  int measured = 0, pivots = 0;
};

// A wall built over its planned length against the truth: missing or not, and off the plan or
// not (with the errors of its offset, angle and pivot where it truly is off).
void gradeWallDeviation(const slam::WallDeviation& wall, const bim::Wall& planned,
                        const bim::AsBuilt& truth, bool truly_missing,
                        const slam::DeviationOptions& options, DeviationGrade& grade,
                        DeviationSums& sums) {
  const bool reported_missing = wall.status == slam::WallStatus::kMissing;
  grade.missing_found += truly_missing && reported_missing;
  grade.missing_false_reports += !truly_missing && reported_missing;
  grade.missing_missed += truly_missing && !reported_missing;
  if (truly_missing || wall.observed_share < grade.min_share || !wall.offset_m) return;
  const bim::Wall built = bim::builtWall(planned, truth);
  const bim::AxisDeviation true_deviation =
      bim::axisDeviation(planned, built.start, built.end - built.start);
  const bool truly_deviating = std::abs(true_deviation.offset_m) >= options.shift_m ||
                               std::abs(true_deviation.angle_deg) >= options.angle_deg;
  const bool reported =
      wall.status == slam::WallStatus::kShifted || wall.status == slam::WallStatus::kRotated;
  ++grade.judged;
  grade.found += truly_deviating && reported;
  grade.false_reports += !truly_deviating && reported;
  grade.missed += truly_deviating && !reported;
  if (truly_deviating) {
    sums.offset_error += std::abs(*wall.offset_m - true_deviation.offset_m);
    sums.angle_error += std::abs(*wall.angle_deg - true_deviation.angle_deg);
    ++sums.measured;
  }
  const double length = (planned.end - planned.start).norm();
  const auto true_pivot =
      slam::crossingAlong(length, true_deviation.offset_m, true_deviation.angle_deg);
  if (std::abs(true_deviation.angle_deg) >= options.angle_deg && wall.pivot_along_m && true_pivot) {
    sums.pivot_error += std::abs(*wall.pivot_along_m - *true_pivot);
    ++sums.pivots;
  }
}

// Extra walls of the levels walked: each reported one found (along a true one), on clutter, or
// false; each true one found or missed.
void gradeExtraWalls(const slam::DeviationReport& report, const bim::AsBuilt& truth,
                     DeviationGrade& grade) {
  const double parallel = std::cos(common::radians(10.0));
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
}

}  // namespace

DeviationGrade gradeDeviations(const slam::DeviationReport& report, const bim::Plan& plan,
                               const bim::AsBuilt& truth) {
  DeviationGrade grade;
  DeviationSums sums;
  LengthErrors partly_errors;
  for (const slam::WallDeviation& wall : report.walls) {
    const bim::Level* level = plan.levelOfWall(wall.wall);
    const bim::Wall* planned = level != nullptr ? level->findWall(wall.wall) : nullptr;
    if (planned == nullptr) continue;
    const auto shortened =
        std::find_if(truth.shortened_walls.begin(), truth.shortened_walls.end(),
                     [&](const bim::ShortenedWall& w) { return w.wall == wall.wall; });
    const bool truly_missing = std::find(truth.missing_walls.begin(), truth.missing_walls.end(),
                                         wall.wall) != truth.missing_walls.end();
    gradeProgress(wall.progress, shortened != truth.shortened_walls.end() ? &*shortened : nullptr,
                  truly_missing, grade, partly_errors);
    // A wall built in part is graded by its progress only: where it stands it may be as planned
    // or not, but not over its planned length.
    if (shortened != truth.shortened_walls.end()) continue;
    gradeWallDeviation(wall, *planned, truth, truly_missing, report.options, grade, sums);
  }
  grade.precision = share(grade.found, grade.found + grade.false_reports);
  grade.recall = share(grade.found, grade.found + grade.missed);
  if (sums.measured > 0) {
    grade.offset_error_m = sums.offset_error / sums.measured;
    grade.angle_error_deg = sums.angle_error / sums.measured;
  }
  if (sums.pivots > 0) grade.pivot_error_m = sums.pivot_error / sums.pivots;
  grade.partly_precision =
      share(grade.partly_found, grade.partly_found + grade.partly_false_reports);
  grade.partly_recall = share(grade.partly_found, grade.partly_found + grade.partly_missed);
  if (partly_errors.measured > 0) {
    grade.built_length_error_m = partly_errors.all / partly_errors.measured;
  }
  if (partly_errors.measured_seen > 0) {
    grade.built_length_error_seen_m = partly_errors.seen / partly_errors.measured_seen;
  }
  gradeExtraWalls(report, truth, grade);
  gradeColumns(report, truth, grade);
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
  for (const auto& w : report.walls) {
    switch (w.progress.status) {
      case slam::ProgressStatus::kBuilt:
        ++m.built;
        break;
      case slam::ProgressStatus::kPartlyBuilt:
        ++m.partly_built;
        break;
      case slam::ProgressStatus::kNotBuilt:
        ++m.not_built;
        break;
      case slam::ProgressStatus::kNotSeen:
        ++m.progress_not_seen;
        break;
    }
  }
  for (const auto& c : report.columns) {
    switch (c.status) {
      case slam::ColumnStatus::kAsPlanned:
        ++m.columns_as_planned;
        break;
      case slam::ColumnStatus::kMoved:
        ++m.columns_moved;
        break;
      case slam::ColumnStatus::kMissing:
        ++m.columns_missing;
        break;
      case slam::ColumnStatus::kNotSeen:
        ++m.columns_not_seen;
        break;
    }
  }
  if (plan != nullptr && truth != nullptr) m.grade = gradeDeviations(report, *plan, *truth);
  return m;
}

namespace {

void putOptional(nlohmann::json& j, const char* key, const std::optional<double>& value) {
  if (value) j[key] = *value;
}

std::optional<double> readShare(const common::JsonNode& node, std::string_view key) {
  if (const auto field = node.optionalField(key)) return field->numberInRange(0.0, 1.0);
  return std::nullopt;
}

std::optional<double> readMeasure(const common::JsonNode& node, std::string_view key) {
  if (const auto field = node.optionalField(key)) return field->nonNegativeNumber();
  return std::nullopt;
}

int readCount(const common::JsonNode& node, std::string_view key) {
  const common::JsonNode field = node.field(key);
  const std::int64_t value = field.integer();
  if (value < 0 || value > 1000000000) field.fail("must be a count, got " + std::to_string(value));
  return int(value);
}

}  // namespace

namespace {

// The file's fields, each written and read once from these tables. A block's counts are required
// when the block is there; its shares and measures are absent when there is nothing to divide by.
template <typename T>
struct Count {
  const char* key;
  int T::*member;
};
struct Optional {
  const char* key;
  std::optional<double> DeviationGrade::*member;
  bool share;  // in [0, 1]; otherwise a non-negative measure
};
constexpr Count<DeviationMetrics> kWallCounts[] = {{"as_planned", &DeviationMetrics::as_planned},
                                                   {"shifted", &DeviationMetrics::shifted},
                                                   {"rotated", &DeviationMetrics::rotated},
                                                   {"missing", &DeviationMetrics::missing},
                                                   {"not_seen", &DeviationMetrics::not_seen}};
constexpr Count<DeviationGrade> kGradedCounts[] = {
    {"judged", &DeviationGrade::judged},
    {"found", &DeviationGrade::found},
    {"false_reports", &DeviationGrade::false_reports},
    {"missed", &DeviationGrade::missed}};
constexpr Optional kGradedOptionals[] = {
    {"precision", &DeviationGrade::precision, true},
    {"recall", &DeviationGrade::recall, true},
    {"offset_error_m", &DeviationGrade::offset_error_m, false},
    {"angle_error_deg", &DeviationGrade::angle_error_deg, false},
    {"pivot_error_m", &DeviationGrade::pivot_error_m, false}};
constexpr Count<DeviationMetrics> kProgressCounts[] = {
    {"built", &DeviationMetrics::built},
    {"partly_built", &DeviationMetrics::partly_built},
    {"not_built", &DeviationMetrics::not_built},
    {"not_seen", &DeviationMetrics::progress_not_seen}};
constexpr Count<DeviationGrade> kPartlyCounts[] = {
    {"found", &DeviationGrade::partly_found},
    {"false_reports", &DeviationGrade::partly_false_reports},
    {"missed", &DeviationGrade::partly_missed}};
constexpr Optional kPartlyOptionals[] = {
    {"precision", &DeviationGrade::partly_precision, true},
    {"recall", &DeviationGrade::partly_recall, true},
    {"built_length_error_m", &DeviationGrade::built_length_error_m, false},
    {"built_length_error_seen_end_to_end_m", &DeviationGrade::built_length_error_seen_m, false}};
constexpr Count<DeviationGrade> kMissingCounts[] = {
    {"found", &DeviationGrade::missing_found},
    {"false_reports", &DeviationGrade::missing_false_reports},
    {"missed", &DeviationGrade::missing_missed}};
constexpr Count<DeviationGrade> kExtraCounts[] = {
    {"found", &DeviationGrade::extra_found},
    {"false_reports", &DeviationGrade::extra_false_reports},
    {"missed", &DeviationGrade::extra_missed},
    {"on_clutter", &DeviationGrade::extra_on_clutter}};
constexpr Optional kExtraOptionals[] = {{"precision", &DeviationGrade::extra_precision, true},
                                        {"recall", &DeviationGrade::extra_recall, true}};
constexpr Count<DeviationMetrics> kColumnCounts[] = {
    {"as_planned", &DeviationMetrics::columns_as_planned},
    {"moved", &DeviationMetrics::columns_moved},
    {"missing", &DeviationMetrics::columns_missing},
    {"not_seen", &DeviationMetrics::columns_not_seen}};
constexpr Count<DeviationGrade> kGradedColumnCounts[] = {
    {"found", &DeviationGrade::column_found},
    {"false_reports", &DeviationGrade::column_false_reports},
    {"missed", &DeviationGrade::column_missed}};
constexpr Optional kGradedColumnOptionals[] = {
    {"precision", &DeviationGrade::column_precision, true},
    {"recall", &DeviationGrade::column_recall, true},
    {"offset_error_m", &DeviationGrade::column_offset_error_m, false}};

template <typename T, std::size_t N>
void putCounts(nlohmann::json& j, const T& from, const Count<T> (&fields)[N]) {
  for (const auto& f : fields) j[f.key] = from.*f.member;
}
template <std::size_t N>
void putOptionals(nlohmann::json& j, const DeviationGrade& from, const Optional (&fields)[N]) {
  for (const auto& f : fields) putOptional(j, f.key, from.*f.member);
}
template <typename T, std::size_t N>
void readCounts(const common::JsonNode& node, T& to, const Count<T> (&fields)[N]) {
  for (const auto& f : fields) to.*f.member = readCount(node, f.key);
}
template <std::size_t N>
void readOptionals(const common::JsonNode& node, DeviationGrade& to, const Optional (&fields)[N]) {
  for (const auto& f : fields) {
    to.*f.member = f.share ? readShare(node, f.key) : readMeasure(node, f.key);
  }
}

}  // namespace

nlohmann::json deviationMetricsJson(const DeviationMetrics& m) {
  nlohmann::json walls = nlohmann::json::object();
  putCounts(walls, m, kWallCounts);
  nlohmann::json progress = nlohmann::json::object();
  putCounts(progress, m, kProgressCounts);
  nlohmann::json j = {{"walls", walls}, {"extra_walls", m.extra_walls}, {"progress", progress}};
  if (m.hasColumns()) {
    nlohmann::json columns = nlohmann::json::object();
    putCounts(columns, m, kColumnCounts);
    j["columns"] = columns;
  }
  if (m.grade) {
    const DeviationGrade& g = *m.grade;
    nlohmann::json graded = {{"min_share", g.min_share}};
    putCounts(graded, g, kGradedCounts);
    putOptionals(graded, g, kGradedOptionals);
    nlohmann::json missing = nlohmann::json::object(), extra = nlohmann::json::object();
    putCounts(missing, g, kMissingCounts);
    putCounts(extra, g, kExtraCounts);
    putOptionals(extra, g, kExtraOptionals);
    nlohmann::json partly = nlohmann::json::object();
    putCounts(partly, g, kPartlyCounts);
    putOptionals(partly, g, kPartlyOptionals);
    graded["missing"] = missing;
    graded["extra"] = extra;
    graded["partly_built"] = partly;
    if (m.hasColumns()) {
      nlohmann::json columns = nlohmann::json::object();
      putCounts(columns, g, kGradedColumnCounts);
      putOptionals(columns, g, kGradedColumnOptionals);
      graded["columns"] = columns;
    }
    j["graded"] = graded;
  }
  return j;
}

DeviationMetrics deviationMetricsFromJson(const common::JsonNode& node) {
  DeviationMetrics m;
  readCounts(node.field("walls"), m, kWallCounts);
  m.extra_walls = readCount(node, "extra_walls");
  // Written since the progress report came in; a metrics.json from before has none.
  if (const auto progress = node.optionalField("progress")) {
    readCounts(*progress, m, kProgressCounts);
  }
  // Written since columns are judged, on plans with columns on the levels walked.
  if (const auto columns = node.optionalField("columns")) {
    readCounts(*columns, m, kColumnCounts);
  }
  if (const auto graded = node.optionalField("graded")) {
    DeviationGrade g;
    g.min_share = graded->field("min_share").numberInRange(0.0, 1.0);
    readCounts(*graded, g, kGradedCounts);
    readOptionals(*graded, g, kGradedOptionals);
    readCounts(graded->field("missing"), g, kMissingCounts);
    readCounts(graded->field("extra"), g, kExtraCounts);
    readOptionals(graded->field("extra"), g, kExtraOptionals);
    if (const auto partly = graded->optionalField("partly_built")) {
      readCounts(*partly, g, kPartlyCounts);
      readOptionals(*partly, g, kPartlyOptionals);
    }
    if (const auto columns = graded->optionalField("columns")) {
      readCounts(*columns, g, kGradedColumnCounts);
      readOptionals(*columns, g, kGradedColumnOptionals);
    }
    m.grade = g;
  }
  return m;
}

}  // namespace isg::run
