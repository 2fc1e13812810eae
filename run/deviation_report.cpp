#include "run/deviation_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "common/angles.hpp"
#include "common/plural.hpp"
#include "common/xml_escape.hpp"
#include "run/off_class_colours.hpp"
#include "run/text_format.hpp"

namespace isg::run {

namespace {

nlohmann::json point(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

const char* colourOf(slam::WallStatus status) {
  switch (status) {
    case slam::WallStatus::kAsPlanned:
      return "#2e8b57";
    case slam::WallStatus::kShifted:
      return "#e67e00";
    case slam::WallStatus::kRotated:
      return "#9b30c8";
    case slam::WallStatus::kMissing:
      return "#d0021b";
    case slam::WallStatus::kNotSeen:
      break;
  }
  return "#b0b0b0";
}

// Every threshold the report judged by, under the names deviations.json gives them.
nlohmann::json thresholdsJson(const slam::DeviationOptions& o) {
  return {{"shift_m", o.shift_m},
          {"angle_deg", o.angle_deg},
          {"noise_factor", o.noise_factor},
          {"min_noise_walls", o.min_noise_walls},
          {"min_angle_length_m", o.min_angle_length},
          {"consistent_tolerance_m", o.consistent_tolerance},
          {"contradiction_observation_share", o.contradiction_observation_share},
          {"min_deviation_observations", o.min_deviation_observations},
          {"max_stray_lean_deg", o.max_stray_lean_deg},
          {"judged_share", o.judged_share},
          {"missing_seen_share", o.missing_seen_share},
          {"missing_view_share", o.missing_view_share},
          {"missing_sight_share", o.missing_sight_share},
          {"min_missing_length_m", o.min_missing_length},
          {"search_distance_m", o.search_distance},
          {"search_angle_deg", o.search_angle_deg},
          {"min_wall_length_m", o.min_wall_length},
          {"column_margin_m", o.column_margin},
          {"bend_distance_m", o.bend_distance},
          {"bend_angle_deg", o.bend_angle_deg},
          {"local_radius_m", o.local_radius},
          {"view_range_m", o.view_range},
          {"max_incidence_deg", o.max_incidence_deg},
          {"min_views", o.min_views},
          {"see_through_margin_m", o.see_through_margin},
          {"window_margin_m", o.window_margin},
          {"extra_pair_distance_m", o.extra_pair_distance},
          {"pivot_name_distance_m", o.pivot_name_distance},
          {"progress_step_m", o.progress_step},
          {"progress_gap_m", o.progress_gap_m},
          {"end_sigma_m", o.end_sigma_m},
          {"clear_factor", o.clear_factor}};
}

// The columns' thresholds (thresholds.columns).
nlohmann::json columnThresholdsJson(const slam::ColumnOptions& c) {
  return {{"search_m", c.search_m},
          {"band_margin_m", c.band_margin_m},
          {"wall_clearance_m", c.wall_clearance_m},
          {"inlier_m", c.inlier_m},
          {"min_points", c.min_points},
          {"min_direction_weight", c.min_direction_weight},
          {"moved_m", c.moved_m},
          {"view_range_m", c.view_range_m},
          {"see_past_margin_m", c.see_past_margin_m},
          {"min_views", c.min_views}};
}

// One wall's entry: its status, measures, evidence, thresholds, progress and pivot.
nlohmann::json wallJson(const slam::WallDeviation& w) {
  nlohmann::json evidence = nlohmann::json::array();
  for (const auto& e : w.evidence) {
    evidence.push_back({{"plane", e.plane},
                        {"face", e.side > 0 ? "left" : "right"},
                        {"length_m", e.length_m},
                        {"observations", e.observations},
                        {"offset_m", e.offset_m},
                        {"angle_deg", e.angle_deg},
                        {"consistent", e.consistent},
                        {"start", point(e.start_B)},
                        {"end", point(e.end_B)}});
  }
  nlohmann::json wall = {
      {"wall", w.wall},
      {"level", w.level},
      {"status", slam::toString(w.status)},
      {"offset_m", w.offset_m ? nlohmann::json(*w.offset_m) : nullptr},
      {"angle_deg", w.angle_deg ? nlohmann::json(*w.angle_deg) : nullptr},
      {"offset_sigma_m", w.offset_sigma_m ? nlohmann::json(*w.offset_sigma_m) : nullptr},
      {"angle_sigma_deg", w.angle_sigma_deg ? nlohmann::json(*w.angle_sigma_deg) : nullptr},
      {"observed_share", w.observed_share},
      {"planned", {{"start", point(w.planned_start)}, {"end", point(w.planned_end)}}},
      {"evidence", evidence}};
  if (w.in_view_share) wall["in_view_share"] = *w.in_view_share;
  if (!w.ifc_guid.empty()) wall["ifc_guid"] = w.ifc_guid;
  if (!w.evidence.empty()) {
    auto optional = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    wall["judged_against"] = {{"shift_m", w.shift_threshold_m},
                              {"angle_deg", w.angle_threshold_deg},
                              {"local_offset_noise_m", optional(w.local_offset_noise_m)},
                              {"local_angle_noise_deg", optional(w.local_angle_noise_deg)},
                              {"placement_sigma_m", w.placement_sigma_m},
                              {"placement_angle_sigma_deg", w.placement_angle_sigma_deg}};
  }
  {
    const slam::WallProgress& p = w.progress;
    nlohmann::json built = nlohmann::json::array();
    for (const auto& [a, b] : p.built) built.push_back({a, b});
    wall["progress"] = {
        {"status", slam::toString(p.status)}, {"planned_m", p.planned_m},   {"built_m", p.built_m},
        {"not_built_m", p.not_built_m},       {"not_seen_m", p.not_seen_m}, {"built", built}};
  }
  if (w.pivot_along_m) {
    const Eigen::Vector2d axis = (w.planned_end - w.planned_start).normalized();
    wall["turned_about"] = {
        {"along_m", *w.pivot_along_m},
        {"sigma_m", w.pivot_sigma_m ? nlohmann::json(*w.pivot_sigma_m) : nullptr},
        {"point", point(w.planned_start + *w.pivot_along_m * axis)},
        {"name", w.turned_about}};
  }
  return wall;
}

nlohmann::json extraWallsJson(const slam::DeviationReport& report) {
  nlohmann::json extra = nlohmann::json::array();
  for (const auto& e : report.extra_walls) {
    extra.push_back({{"level", e.level},
                     {"start", point(e.start)},
                     {"end", point(e.end)},
                     {"length_m", e.length()},
                     {"planes", e.planes}});
  }
  return extra;
}

nlohmann::json placementsJson(const slam::DeviationReport& report) {
  nlohmann::json placements = nlohmann::json::array();
  for (const auto& p : report.placements) {
    placements.push_back({{"level", p.level},
                          {"x", p.correction.x()},
                          {"y", p.correction.y()},
                          {"yaw_deg", common::degrees(p.correction.z())},
                          {"walls_used", p.walls_used}});
  }
  return placements;
}

nlohmann::json columnsJson(const slam::DeviationReport& report) {
  nlohmann::json columns = nlohmann::json::array();
  for (const auto& c : report.columns) {
    columns.push_back({{"column", c.column},
                       {"level", c.level},
                       {"shape", c.round ? "round" : "rectangle"},
                       {"status", slam::toString(c.status)},
                       {"planned_centre", point(c.planned_centre)},
                       {"points", c.points},
                       {"offset_m", c.offset_m ? point(*c.offset_m) : nlohmann::json()},
                       {"directions_measured", c.directions_measured},
                       {"seen_past", c.seen_past}});
    if (!c.ifc_guid.empty()) columns.back()["ifc_guid"] = c.ifc_guid;
  }
  return columns;
}

// The map against the plan, level by level, with its face stretches.
nlohmann::json againstPlanJson(const slam::DeviationReport& report) {
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& level : report.against_plan) {
    nlohmann::json stretches = nlohmann::json::array();
    for (const auto& s : level.stretches) {
      stretches.push_back({{"surface", s.surface},
                           {"start", point(s.start)},
                           {"end", point(s.end)},
                           {"points", s.points},
                           {"mean_m", s.mean_m},
                           {"rms_m", s.rms_m}});
    }
    levels.push_back({{"level", level.level},
                      {"points", level.points},
                      {"near_share", level.near_share},
                      {"cutoff_m", level.cutoff_m},
                      {"median_m", level.median_m},
                      {"p95_m", level.p95_m},
                      {"stretches", stretches}});
  }
  return levels;
}

}  // namespace

nlohmann::json deviationReportJson(const slam::DeviationReport& report) {
  nlohmann::json walls = nlohmann::json::array();
  for (const auto& w : report.walls) walls.push_back(wallJson(w));
  nlohmann::json out = {{"format", "isg.deviations"},
                        {"version", 1},
                        {"frame", "B"},
                        {"levels", report.levels},
                        {"thresholds", thresholdsJson(report.options)},
                        {"placement_correction", placementsJson(report)},
                        {"walls", walls},
                        {"extra_walls", extraWallsJson(report)}};
  if (!report.columns.empty()) {
    out["columns"] = columnsJson(report);
    out["thresholds"]["columns"] = columnThresholdsJson(report.column_options);
  }
  if (!report.against_plan.empty()) out["map_against_plan"] = againstPlanJson(report);
  return out;
}

namespace {

constexpr double kSvgScale = 40.0;  // px per metre
constexpr double kSvgMargin = 30.0, kSvgTitle = 24.0, kSvgLegend = 70.0;

// One level's drawing: its name and the box of what it shows.
struct DeviationPanel {
  std::string level;
  Eigen::AlignedBox2d box;
};

std::vector<DeviationPanel> deviationPanels(const slam::DeviationReport& report) {
  std::vector<DeviationPanel> panels;
  for (const auto& level : report.levels) {
    DeviationPanel panel{level, {}};
    for (const auto& w : report.walls) {
      if (w.level != level) continue;
      panel.box.extend(w.planned_start);
      panel.box.extend(w.planned_end);
      for (const auto& e : w.evidence) panel.box.extend(e.start_B), panel.box.extend(e.end_B);
    }
    for (const auto& e : report.extra_walls) {
      if (e.level == level) panel.box.extend(e.start), panel.box.extend(e.end);
    }
    for (const auto& c : report.columns) {
      if (c.level != level) continue;
      for (const auto& p : c.planned_outline) panel.box.extend(p);
    }
    if (!panel.box.isEmpty()) panels.push_back(panel);
  }
  return panels;
}

// The title, the thresholds and the colours' legend.
std::string deviationLegend(const slam::DeviationOptions& o) {
  std::string svg = format(
      "<text x=\"10\" y=\"18\" font-size=\"13\">As built against the plan (frame B): shifted "
      "at |offset| &#8805; %.2f m, rotated at |angle| &#8805; %.1f&#176; (or %.0f&#215; the "
      "map's own error around the wall, where larger)</text>\n",
      o.shift_m, o.angle_deg, o.noise_factor);
  const std::pair<slam::WallStatus, const char*> legend[] = {
      {slam::WallStatus::kAsPlanned, "as planned"},
      {slam::WallStatus::kShifted, "shifted"},
      {slam::WallStatus::kRotated, "rotated"},
      {slam::WallStatus::kMissing, "missing"},
      {slam::WallStatus::kNotSeen, "not seen"}};
  double x = 10.0;
  for (const auto& [status, name] : legend) {
    svg += format(
        "<line x1=\"%.0f\" y1=\"38\" x2=\"%.0f\" y2=\"38\" stroke=\"%s\" stroke-width=\"4\"/>"
        "<text x=\"%.0f\" y=\"42\">%s</text>\n",
        x, x + 20, colourOf(status), x + 25, name);
    x += 95.0;
  }
  svg += format(
      "<line x1=\"%.0f\" y1=\"38\" x2=\"%.0f\" y2=\"38\" stroke=\"#1f5fd0\" stroke-width=\"4\"/>"
      "<text x=\"%.0f\" y=\"42\">extra wall</text>\n",
      x, x + 20, x + 25);
  return svg +
         "<text x=\"10\" y=\"60\" fill=\"#555\">grey: the plan's walls; coloured: the map's "
         "walls seen as each plan wall, by its status; columns: outlined in their status's "
         "colour, a moved one filled where it stands, a missing one dashed</text>\n";
}

// A column's status drawn in the colour of the wall status it is like: moved as shifted.
slam::WallStatus columnColourStatus(slam::ColumnStatus status) {
  switch (status) {
    case slam::ColumnStatus::kAsPlanned:
      return slam::WallStatus::kAsPlanned;
    case slam::ColumnStatus::kMoved:
      return slam::WallStatus::kShifted;
    case slam::ColumnStatus::kMissing:
      return slam::WallStatus::kMissing;
    case slam::ColumnStatus::kNotSeen:
      break;
  }
  return slam::WallStatus::kNotSeen;
}

// A wall's label: its id, and its offset and angle when it deviates.
std::string wallLabel(const slam::WallDeviation& w) {
  std::string label = common::xmlEscape(w.wall);
  if ((w.status == slam::WallStatus::kShifted || w.status == slam::WallStatus::kRotated) &&
      w.offset_m && w.angle_deg) {
    label += format(" %+.2f m %+.1f&#176;", *w.offset_m, *w.angle_deg);
    if (w.pivot_along_m) {
      label += w.turned_about == "along" || w.turned_about == "beyond"
                   ? format(" about %.1f m along", *w.pivot_along_m)
                   : " about its " + w.turned_about;
    }
  } else if (w.status == slam::WallStatus::kMissing) {
    label += " missing";
  }
  return label;
}

// One level's panel, its top at `top`: the planned walls in grey (a missing one dashed in its
// colour), the map's walls over them coloured by status, the extra walls.
std::string deviationPanel(const slam::DeviationReport& report, const DeviationPanel& panel,
                           double top) {
  auto X = [&](const Eigen::Vector2d& p) {
    return kSvgMargin + (p.x() - panel.box.min().x()) * kSvgScale;
  };
  auto Y = [&](const Eigen::Vector2d& p) {
    return top + kSvgTitle + kSvgMargin + (panel.box.max().y() - p.y()) * kSvgScale;
  };
  std::string svg = format("<text x=\"10\" y=\"%.0f\" font-size=\"12\">Level %s</text>\n", top + 16,
                           common::xmlEscape(panel.level).c_str());
  for (const auto& w : report.walls) {
    if (w.level != panel.level) continue;
    const bool missing = w.status == slam::WallStatus::kMissing;
    svg += format(
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
        "stroke-width=\"%.1f\"%s/>\n",
        X(w.planned_start), Y(w.planned_start), X(w.planned_end), Y(w.planned_end),
        missing ? colourOf(w.status) : "#c8c8c8", std::max(2.0, w.thickness * kSvgScale),
        missing ? " stroke-dasharray=\"6 4\" stroke-opacity=\"0.6\"" : "");
    for (const auto& e : w.evidence) {
      svg += format(
          "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
          "stroke-width=\"2.5\"/>\n",
          X(e.start_B), Y(e.start_B), X(e.end_B), Y(e.end_B), colourOf(w.status));
    }
    const Eigen::Vector2d middle = 0.5 * (w.planned_start + w.planned_end);
    svg +=
        format("<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\">%s</text>\n", X(middle) + 4, Y(middle) - 4,
               w.status == slam::WallStatus::kAsPlanned ? "#777" : colourOf(w.status),
               wallLabel(w).c_str());
  }
  // The columns: the planned outline in its status's colour (dashed when missing), a moved one
  // filled where it was found, labelled with its offset.
  for (const auto& c : report.columns) {
    if (c.level != panel.level || c.planned_outline.empty()) continue;
    const slam::WallStatus as_wall = columnColourStatus(c.status);
    auto outline = [&](const Eigen::Vector2d& offset) {
      std::string points;
      for (const auto& p : c.planned_outline) {
        points += format("%.1f,%.1f ", X(p + offset), Y(p + offset));
      }
      return points;
    };
    const bool missing = c.status == slam::ColumnStatus::kMissing;
    svg += format("<polygon points=\"%s\" fill=\"%s\" stroke=\"%s\" stroke-width=\"1.5\"%s/>\n",
                  outline(Eigen::Vector2d::Zero()).c_str(),
                  c.status == slam::ColumnStatus::kAsPlanned ? "#c8c8c8" : "none",
                  colourOf(as_wall), missing ? " stroke-dasharray=\"3 2\"" : "");
    if (c.status == slam::ColumnStatus::kMoved && c.offset_m) {
      svg += format("<polygon points=\"%s\" fill=\"%s\" fill-opacity=\"0.7\"/>\n",
                    outline(*c.offset_m).c_str(), colourOf(as_wall));
    }
    if (c.status == slam::ColumnStatus::kMoved || missing) {
      std::string label = common::xmlEscape(c.column);
      label += missing ? std::string(" missing")
                       : format(" moved %+.2f, %+.2f m", c.offset_m->x(), c.offset_m->y());
      svg += format("<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\">%s</text>\n", X(c.planned_centre) + 10,
                    Y(c.planned_centre) - 8, colourOf(as_wall), label.c_str());
    }
  }
  for (const auto& e : report.extra_walls) {
    if (e.level != panel.level) continue;
    svg += format(
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#1f5fd0\" "
        "stroke-width=\"3\"/>\n",
        X(e.start), Y(e.start), X(e.end), Y(e.end));
    const Eigen::Vector2d middle = 0.5 * (e.start + e.end);
    svg += format("<text x=\"%.1f\" y=\"%.1f\" fill=\"#1f5fd0\">extra %.1f m</text>\n",
                  X(middle) + 4, Y(middle) + 12, e.length());
  }
  return svg;
}

// One level's map against the plan, its top at `top`: the plan's walls in grey, each face's
// stretches coloured by how far the map's points lie off it, the five farthest labelled.
std::string againstPlanPanel(const slam::DeviationReport& report,
                             const slam::LevelAgainstPlan& level, const DeviationPanel& panel,
                             double top) {
  auto X = [&](const Eigen::Vector2d& p) {
    return kSvgMargin + (p.x() - panel.box.min().x()) * kSvgScale;
  };
  auto Y = [&](const Eigen::Vector2d& p) {
    return top + kSvgTitle + kSvgMargin + (panel.box.max().y() - p.y()) * kSvgScale;
  };
  std::string svg = format(
      "<text x=\"10\" y=\"%.0f\" font-size=\"12\">Level %s, the map against the plan: "
      "median %.3f m, 95 %% within %.3f m, %.0f %% of the map's wall points within %.2f m of "
      "a face</text>\n",
      top + 16, common::xmlEscape(level.level).c_str(), level.median_m, level.p95_m,
      100.0 * level.near_share, level.cutoff_m);
  double x = 10.0;
  const char* names[4] = {"within 2 cm", "2-4 cm", "4-8 cm", "8 cm and more"};
  for (int c = 0; c < 4; ++c) {
    svg += format(
        "<line x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\" stroke=\"%s\" "
        "stroke-width=\"4\"/><text x=\"%.0f\" y=\"%.0f\">%s</text>\n",
        x, top + 30, x + 20, top + 30, offClassHex(c).c_str(), x + 25, top + 34, names[c]);
    x += 110.0;
  }
  for (const auto& w : report.walls) {
    if (w.level != panel.level) continue;
    svg += format(
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#d8d8d8\" "
        "stroke-width=\"%.1f\"/>\n",
        X(w.planned_start), Y(w.planned_start), X(w.planned_end), Y(w.planned_end),
        std::max(2.0, w.thickness * kSvgScale));
  }
  for (const auto& s : level.stretches) {
    svg += format(
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
        "stroke-width=\"3\"/>\n",
        X(s.start), Y(s.start), X(s.end), Y(s.end), offClassHex(slam::offClass(s.mean_m)).c_str());
  }
  std::vector<const slam::FaceStretch*> farthest;
  for (const auto& s : level.stretches) {
    if (slam::offClass(s.mean_m) >= 2) farthest.push_back(&s);
  }
  std::sort(farthest.begin(), farthest.end(),
            [](const auto* a, const auto* b) { return std::abs(a->mean_m) > std::abs(b->mean_m); });
  if (farthest.size() > 5) farthest.resize(5);
  for (const auto* s : farthest) {
    const Eigen::Vector2d middle = 0.5 * (s->start + s->end);
    svg += format("<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\">%s %+.2f m</text>\n", X(middle) + 4,
                  Y(middle) - 4, offClassHex(slam::offClass(s->mean_m)).c_str(),
                  common::xmlEscape(s->surface).c_str(), s->mean_m);
  }
  return svg;
}

}  // namespace

std::string deviationSvg(const slam::DeviationReport& report) {
  const std::vector<DeviationPanel> panels = deviationPanels(report);
  double width = 400.0, height = kSvgLegend;
  auto againstPlanOf = [&](const std::string& level) -> const slam::LevelAgainstPlan* {
    for (const auto& on : report.against_plan) {
      if (on.level == level) return &on;
    }
    return nullptr;
  };
  for (const auto& p : panels) {
    width = std::max(width, p.box.sizes().x() * kSvgScale + 2 * kSvgMargin);
    const double panel_height = p.box.sizes().y() * kSvgScale + 2 * kSvgMargin + kSvgTitle;
    height += againstPlanOf(p.level) ? 2 * panel_height : panel_height;
  }
  if (!report.against_plan.empty()) width = std::max(width, 820.0);
  std::string svg = format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
      "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"11\">\n"
      "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
      width, height, width, height);
  svg += deviationLegend(report.options);
  double top = kSvgLegend;
  for (const auto& panel : panels) {
    const double panel_height = panel.box.sizes().y() * kSvgScale + 2 * kSvgMargin + kSvgTitle;
    svg += deviationPanel(report, panel, top);
    top += panel_height;
    if (const slam::LevelAgainstPlan* against = againstPlanOf(panel.level)) {
      svg += againstPlanPanel(report, *against, panel, top);
      top += panel_height;
    }
  }
  return svg + "</svg>\n";
}

std::string progressSummaryLine(const DeviationMetrics& m) {
  std::string line = format("progress: %s built, %d partly built, %d not built, %d not seen",
                            common::counted(m.built, "wall").c_str(), m.partly_built, m.not_built,
                            m.progress_not_seen);
  if (m.grade && m.grade->built_length_error_m) {
    line += format(
        "; against the truth: %d of %d walls built in part found, %d falsely (built "
        "lengths off by %.2f m)",
        m.grade->partly_found, m.grade->partly_found + m.grade->partly_missed,
        m.grade->partly_false_reports, *m.grade->built_length_error_m);
  } else if (m.grade) {
    line += format("; against the truth: %d of %d walls built in part found, %d falsely",
                   m.grade->partly_found, m.grade->partly_found + m.grade->partly_missed,
                   m.grade->partly_false_reports);
  }
  return line;
}

std::string columnSummaryLine(const DeviationMetrics& m) {
  std::string line =
      format("columns: %d as planned, %d moved, %d missing, %d not seen", m.columns_as_planned,
             m.columns_moved, m.columns_missing, m.columns_not_seen);
  if (m.grade) {
    const DeviationGrade& g = *m.grade;
    line += format("; against the truth: %d of %d deviating columns found, %d falsely",
                   g.column_found, g.column_found + g.column_missed, g.column_false_reports);
    if (g.column_offset_error_m) {
      line += format(" (offsets off by %.3f m)", *g.column_offset_error_m);
    }
  }
  return line;
}

std::string deviationSummaryLine(const DeviationMetrics& m) {
  std::string line = format(
      "as built against the plan: %s as planned, %d shifted, %d rotated, %d missing, %d "
      "not seen; %s",
      common::counted(m.as_planned, "wall").c_str(), m.shifted, m.rotated, m.missing, m.not_seen,
      common::counted(m.extra_walls, "extra wall").c_str());
  if (m.grade) {
    const DeviationGrade& g = *m.grade;
    line += format("; against the truth: %d of %d deviating walls found, %d falsely", g.found,
                   g.found + g.missed, g.false_reports);
    if (g.offset_error_m && g.angle_error_deg) {
      line +=
          format(" (offsets off by %.3f m, angles by %.2f°", *g.offset_error_m, *g.angle_error_deg);
      if (g.pivot_error_m) line += format(", the turns' pivots by %.2f m", *g.pivot_error_m);
      line += ")";
    }
  }
  return line;
}

}  // namespace isg::run
