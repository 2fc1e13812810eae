#include "run/run_report.hpp"

#include "common/plural.hpp"
#include "run/deviation_report.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"
#include "eval/report_svg.hpp"
#include "run/builtin_methods.hpp"
#include "run/map_plan_error.hpp"
#include "run/text_format.hpp"

namespace isg::run {

namespace {

// ", after 6.2 m and 2 rooms": what the robot had walked by its first localization.
std::string walkedBy(const RunMetrics& m) {
  if (!m.distance_to_localize) return "";
  std::string out = format(", after %.1f m", *m.distance_to_localize);
  if (m.rooms_visited_to_localize) {
    out += format(" and %d room%s", *m.rooms_visited_to_localize,
                  *m.rooms_visited_to_localize == 1 ? "" : "s");
  }
  return out;
}

}  // namespace

namespace {

std::vector<Eigen::Vector2d> rectangle(const Eigen::Vector2d& centre, const Eigen::Vector2d& along,
                                       double half_length, double half_width) {
  const Eigen::Vector2d u = along.normalized();
  const Eigen::Vector2d n(-u.y(), u.x());
  return {centre - half_length * u - half_width * n, centre + half_length * u - half_width * n,
          centre + half_length * u + half_width * n, centre - half_length * u + half_width * n};
}

// What was built differently from the plan on `level`, as shapes over the plan's walls.
std::vector<eval::MapOverlay> asBuiltOverlays(const bim::Level& level,
                                              const bim::LevelGeometry& geometry,
                                              const bim::AsBuilt& as_built) {
  using Kind = eval::MapOverlay::Kind;
  std::vector<eval::MapOverlay> out;
  for (const auto& id : as_built.missing_walls) {
    if (const auto* wall = geometry.findWall(id))
      out.push_back({Kind::kMissingWall, wall->footprint()});
  }
  // The parts of a wall built only in part that are not there yet, drawn as missing.
  for (const auto& shortened : as_built.shortened_walls) {
    const auto* wall = geometry.findWall(shortened.wall);
    if (wall == nullptr) continue;
    double from = 0.0;
    const auto gap = [&](double lo, double hi) {
      if (hi - lo < 1e-6) return;
      out.push_back({Kind::kMissingWall, rectangle(wall->pointAt(0.5 * (lo + hi)), wall->axis,
                                                   0.5 * (hi - lo), 0.5 * wall->wall->thickness)});
    };
    for (const auto& [lo, hi] : shortened.built) {
      gap(from, lo);
      from = hi;
    }
    gap(from, wall->length);
  }
  for (const auto& shift : as_built.wall_shifts) {
    const auto* wall = geometry.findWall(shift.wall);
    if (wall == nullptr) continue;
    for (auto piece : wall->footprintPieces()) {
      for (auto& p : piece) p += shift.offset * wall->left_normal;
      out.push_back({Kind::kShiftedWall, piece});
    }
  }
  for (const auto& extra : as_built.extra_walls) {
    if (extra.level != level.id || (extra.end - extra.start).norm() < 1e-9) continue;
    out.push_back({Kind::kExtraWall,
                   rectangle(0.5 * (extra.start + extra.end), extra.end - extra.start,
                             0.5 * (extra.end - extra.start).norm(), 0.5 * extra.thickness)});
  }
  for (const auto& id : as_built.closed_doors) {
    for (const auto& door : level.doors) {
      if (door.id != id) continue;
      const auto* wall = geometry.findWall(door.wall);
      if (wall == nullptr) continue;
      // The leaf, 4 cm thick, across the opening in the middle of the wall.
      double offset = 0.0;
      for (const auto& shift : as_built.wall_shifts) {
        if (shift.wall == door.wall) offset = shift.offset;
      }
      out.push_back(
          {Kind::kClosedDoor, rectangle(wall->pointAt(door.offset) + offset * wall->left_normal,
                                        wall->axis, 0.5 * door.width, 0.02)});
    }
  }
  for (const auto& box : as_built.clutter) {
    if (box.level != level.id) continue;
    const Eigen::Vector2d along(std::cos(box.yaw), std::sin(box.yaw));
    out.push_back({Kind::kClutter,
                   rectangle(box.center.head<2>(), along, 0.5 * box.size.x(), 0.5 * box.size.y())});
  }
  return out;
}

// A level's map for the report: its walls with their door openings, what was built differently,
// and its room names (at the A-Graph's room centres when there is one).
eval::StoreyPanel storeyPanel(const bim::Level& level, const RunSetup& setup) {
  eval::StoreyPanel panel;
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  for (const auto& wall : geometry.walls) {
    for (auto& piece : wall.footprintPieces()) panel.walls.push_back(std::move(piece));
  }
  for (const auto& column : level.columns) {  // rectangular ones are among the walls
    if (column.round()) panel.walls.push_back(bim::columnFootprint(column));
  }
  if (setup.as_built != nullptr) panel.overlays = asBuiltOverlays(level, geometry, *setup.as_built);
  for (const auto& room : level.rooms) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : room.outline) centre += p / double(room.outline.size());
    if (setup.agraph != nullptr) {
      for (const auto& node : setup.agraph->rooms) {
        if (node.id == room.id && node.level == level.id) centre = node.centre;
      }
    }
    panel.labels.push_back({room.id, centre, room.outline});
  }
  return panel;
}

// "Level L1 (elevation 3.2 m): 120.4 s there, APE in B rmse 0.021 m, max 0.05 m; map against the
// plan: median 0.017 m, 95 % within 0.057 m" from metrics.json's levels and map_to_plan.levels.
std::string storeyTitle(const bim::Level& level, const RunMetrics& m) {
  std::string title = "Level " + level.id;
  title += format(" (elevation %.2f m)", level.elevation);
  const auto measured = std::find_if(m.levels.begin(), m.levels.end(),
                                     [&](const LevelMetrics& l) { return l.level == level.id; });
  if (measured == m.levels.end()) {
    title += ": not visited";
  } else {
    title += format(": %.1f s there", measured->seconds);
    title += measured->ape_B ? format(", APE in B rmse %.3f m, max %.3f m", measured->ape_B->rmse,
                                      measured->ape_B->max)
                             : std::string(", no pose in B");
  }
  if (m.map_to_plan) {
    for (const auto& on : m.map_to_plan->levels) {
      if (on.level != level.id) continue;
      title += format("; map against the plan: median %.3f m, 95 %% within %.3f m", on.median_m,
                      on.p95_m);
    }
  }
  return title;
}

std::string mapToPlanLine(const RunMetrics::MapToPlan& map) {
  return format(
      "map against the plan's walls: rmse %.3f m over the %.0f %% of its %lld points in their "
      "height band that lie within %.2f m of one",
      map.distance.rmse, 100.0 * map.near_share, static_cast<long long>(map.points), map.cutoff);
}

// "on L0: median 0.017 m, 95 % within 0.057 m; 9 of 85 face stretches 4 cm off or more (8.5 m),
// the farthest W4:left -0.07 m": where on a level the map lies off the plan.
std::string mapToPlanLevelLine(const RunMetrics::MapToPlan::Level& level) {
  std::string line = format("on %s: median %.3f m, 95 %% within %.3f m", level.level.c_str(),
                            level.median_m, level.p95_m);
  if (level.stretches == 0) return line + "; no face stretch with enough points";
  line +=
      format("; %d of %d face stretches 4 cm off or more", level.off_stretches, level.stretches);
  if (level.off_stretches > 0) line += format(" (%.1f m)", level.off_length_m);
  if (level.farthest) {
    line += format(", the farthest %s %+.2f m", level.farthest->surface.c_str(),
                   level.farthest->mean_m);
  }
  return line;
}

// The map's wall-band points placed in B, only the ones the report draws: counted first, then
// every reportDotStep-th of each panel's kept (each storey's, or the one map's). The same dots as
// drawing from all of them, without holding a long run's millions of points.
std::vector<Eigen::Vector3d> drawnMapPoints(const RunRecord& run,
                                            const std::vector<eval::StoreyPanel>& storeys) {
  auto panelOf = [&](const Eigen::Vector3d& p) {
    for (std::size_t k = 0; k < storeys.size(); ++k) {
      if (p.z() >= storeys[k].z_min && p.z() < storeys[k].z_max) return k;
    }
    return storeys.empty() ? std::size_t(0) : storeys.size();  // on no panel: never drawn
  };
  std::vector<std::size_t> count(std::max<std::size_t>(1, storeys.size()) + 1, 0);
  forEachWallBandMapPoint(run, {}, [&](const Eigen::Vector3d& p) { ++count[panelOf(p)]; });
  std::vector<std::size_t> seen(count.size(), 0);
  std::vector<Eigen::Vector3d> out;
  forEachWallBandMapPoint(run, {}, [&](const Eigen::Vector3d& p) {
    const std::size_t k = panelOf(p);
    if (k + 1 < count.size() && seen[k]++ % eval::reportDotStep(count[k]) == 0) out.push_back(p);
  });
  return out;
}

}  // namespace

std::string reportSvg(const RunRecord& run, const RunEvaluation& evaluation) {
  const RunMetrics& m = evaluation.metrics;
  eval::ReportInput input;
  input.title = "isg run: " + run.setup.world + " — " + run.setup.method;
  if (m.localized && m.ape_B) {
    input.summary.push_back(format(
        "localized at t = %.1f s%s (%.0f %% of the run); APE in B (2D, no alignment) rmse %.3f "
        "m, max %.3f m",
        *m.time_to_localize, walkedBy(m).c_str(), 100.0 * *m.share_localized, m.ape_B->rmse,
        m.ape_B->max));
  } else if (m.localized) {
    input.summary.push_back(format("localized at t = %.1f s (%.0f %% of the run); no APE",
                                   *m.time_to_localize, 100.0 * *m.share_localized));
  } else {
    input.summary.push_back("never localized in the plan");
  }
  if (m.wrongly_localized && *m.wrongly_localized) {
    input.summary.push_back(format("WRONGLY LOCALIZED: %.1f s more than 1 m off (max %.2f m)",
                                   *m.time_wrongly_localized, *m.max_error_B));
  }
  if (m.map_to_plan) input.summary.push_back(mapToPlanLine(*m.map_to_plan));
  if (run.streams.ground_truth.empty()) input.empty_chart_text = "no ground truth: no APE";
  if (m.ape_odometry_from_true_start) {
    input.summary.push_back(
        format("odometry from the true start: APE rmse %.3f m; %.1f s of robot time in %.1f s "
               "(%.1fx real time), seed %llu",
               m.ape_odometry_from_true_start->rmse, m.sim_seconds, m.wall_seconds,
               m.real_time_factor, static_cast<unsigned long long>(m.seed)));
  }
  if (const bim::Plan* plan = run.setup.plan; plan != nullptr && plan->levels.size() > 1) {
    // A panel per storey, lowest first; each holds the poses from its floor up to the next.
    std::vector<const bim::Level*> levels;
    for (const auto& level : plan->levels) levels.push_back(&level);
    std::stable_sort(levels.begin(), levels.end(), [](const bim::Level* a, const bim::Level* b) {
      return a->elevation < b->elevation;
    });
    for (std::size_t k = 0; k < levels.size(); ++k) {
      eval::StoreyPanel panel = storeyPanel(*levels[k], run.setup);
      panel.z_min = k == 0 ? -std::numeric_limits<double>::infinity() : levels[k]->elevation;
      panel.z_max = k + 1 == levels.size() ? std::numeric_limits<double>::infinity()
                                           : levels[k + 1]->elevation;
      panel.title = storeyTitle(*levels[k], m);
      input.storeys.push_back(std::move(panel));
    }
  } else if (plan != nullptr) {
    const bim::Level* level = plan->findLevel(run.setup.level);
    if (level == nullptr && !plan->levels.empty()) level = &plan->levels[0];
    if (level != nullptr) {
      eval::StoreyPanel panel = storeyPanel(*level, run.setup);
      input.walls = std::move(panel.walls);
      input.overlays = std::move(panel.overlays);
      input.labels = std::move(panel.labels);
    }
  }
  input.map_points = drawnMapPoints(run, input.storeys);
  input.ground_truth = run.streams.ground_truth;
  if (evaluation.dead_reckoning_B_T_M) {
    input.odometry = run.streams.odometry;
    input.odometry_placement = evaluation.dead_reckoning_B_T_M;
  }
  input.localized_at = run.localized_at;
  const MethodInfo* method = builtinMethods().find(run.setup.method);
  Trajectory aligned_map_estimate;  // outlives eval::reportSvg below, which views it
  if (method != nullptr && method->slam_only && evaluation.map_alignment) {
    // A method that does not localize in the plan (SLAM only): its map, aligned after the fact.
    aligned_map_estimate.reserve(run.estimate_map.size());
    for (const auto& pose : run.estimate_map) {
      aligned_map_estimate.push_back({pose.t, evaluation.map_alignment->apply(pose.pose)});
    }
    input.estimate = aligned_map_estimate;
    input.estimate_is_localization = false;
    input.estimate_label = "estimate in M, SE(3)-aligned to the ground truth";
    input.error_title = "APE in M after SE(3) alignment";
    input.error_over_time = evaluation.map_error_over_time;
    input.heading_error_over_time = evaluation.map_heading_error_over_time;
    input.summary[0] = format(
        "%s does not localize in the plan: drawn is its map-frame estimate, SE(3)-aligned to the",
        run.setup.method.c_str());
    input.summary.insert(
        input.summary.begin() + 1,
        format("ground truth after the run: APE in M rmse %.3f m — the map's quality, not a "
               "localization",
               m.ape_M_se3 ? m.ape_M_se3->rmse : 0.0));
  } else {
    input.estimate = run.estimate;
    input.error_over_time = evaluation.error_over_time;
    input.heading_error_over_time = evaluation.heading_error_over_time;
  }
  return eval::reportSvg(input);
}

std::string timingTable(const RunMetrics& m, double writing_seconds) {
  if (!m.timing) return "";
  const RunTiming& t = *m.timing;
  const double robot = m.sim_seconds > 0 ? m.sim_seconds : 1.0;
  std::string out = format(
      "  where the time went (%.1f s of robot time; %d of %s read, the others never made):\n"
      "    %-22s %9s %14s\n",
      m.sim_seconds, t.scans_read, common::counted(m.scans, "scan").c_str(), "stage", "seconds",
      "ms per robot-s");
  double total = 0.0;
  auto row = [&](const std::string& stage, double seconds) {
    out += format("    %-22s %9.2f %14.2f\n", stage.c_str(), seconds, 1e3 * seconds / robot);
  };
  for (const auto& s : t.stages) {
    row(s.stage, s.seconds);
    total += s.seconds;
  }
  row("writing the run folder", writing_seconds);
  total += writing_seconds;
  row("all stages", total);
  out += format(
      "    the loop: %.2f s of wall time; its thread %.2f s in the localizer, %.2f s waiting for "
      "(or making) scans\n",
      m.wall_seconds, t.localizer_seconds, t.scan_wait_seconds);
  if (t.peak_memory_mb) out += format("    peak memory: %.0f MB\n", *t.peak_memory_mb);
  return out;
}

namespace {

// Said only when the plan did not confirm every pose: the share of poses in each state, their APE
// in B, and the keyframes the as-built report left out.
std::string estimateStatesLine(const RunMetrics& m) {
  if (!m.estimate_states) return "";
  const RunMetrics::EstimateStates& e = *m.estimate_states;
  std::int64_t poses = 0;
  for (const auto& s : e.states) poses += s.poses;
  if (poses == 0 || (e.states.size() == 1 && e.states[0].state == "localized")) return "";
  std::string out =
      format("  an estimate for %.1f %% of the walk from then on:", 100.0 * e.coverage_from_first);
  for (std::size_t i = 0; i < e.states.size(); ++i) {
    const auto& s = e.states[i];
    out += format("%s %s %.1f %%", i > 0 ? "," : "", s.state.c_str(), 100.0 * s.poses / poses);
    if (s.ape_B) out += format(" (APE rmse %.3f m, max %.3f m)", s.ape_B->rmse, s.ape_B->max);
  }
  out += "\n";
  if (e.keyframes_left_out > 0) {
    out +=
        format("  %lld keyframes placed without the plan's confirmation left out of the report\n",
               static_cast<long long>(e.keyframes_left_out));
  }
  return out;
}

}  // namespace

std::string runSummary(const std::string& command, const std::string& dir, const RunMetrics& m) {
  std::string out =
      format("%s: wrote %s (%s on %s, seed %llu)\n", command.c_str(), dir.c_str(), m.method.c_str(),
             m.world.c_str(), static_cast<unsigned long long>(m.seed));
  if (m.localized) {
    out += format("  localized at t = %.1f s%s (%.0f %% of the run localized)\n",
                  *m.time_to_localize, walkedBy(m).c_str(), 100.0 * *m.share_localized);
    if (m.ape_B) {
      out += format(
          "  APE in B (2D, no alignment, from then on): rmse %.3f m, median %.3f m, max %.3f m "
          "over %d poses\n",
          m.ape_B->rmse, m.ape_B->median, m.ape_B->max, m.ape_B->count);
    }
    out += estimateStatesLine(m);
    if (m.wrongly_localized && *m.wrongly_localized) {
      out += format("  WRONGLY LOCALIZED: %.1f s with the pose more than 1 m off (max %.2f m)\n",
                    *m.time_wrongly_localized, *m.max_error_B);
    } else if (m.time_wrongly_localized && *m.time_wrongly_localized > 0) {
      out += format("  more than 1 m off for %.1f s in all, never 5 s on end\n",
                    *m.time_wrongly_localized);
    }
  } else {
    out += "  not localized in the plan";
    if (m.matching_status) out += " (matching: " + *m.matching_status + ")";
    out += "\n";
  }
  if (!m.lost_at.empty()) {
    std::string times;
    for (std::size_t i = 0; i < m.lost_at.size(); ++i) {
      times += format("%s%.1f s", i ? ", " : "", m.lost_at[i]);
      if (i < m.relocalized_at.size())
        times += format(" (relocalized at %.1f s)", m.relocalized_at[i]);
    }
    out += "  lost at " + times + "\n";
  }
  if (m.map_to_plan) {
    out += "  " + mapToPlanLine(*m.map_to_plan) + "\n";
    for (const auto& level : m.map_to_plan->levels) {
      out += "    " + mapToPlanLevelLine(level) + "\n";
    }
  }
  if (m.deviations) {
    out += "  " + deviationSummaryLine(*m.deviations) + "\n";
    out += "  " + progressSummaryLine(*m.deviations) + "\n";
    if (m.deviations->hasColumns()) out += "  " + columnSummaryLine(*m.deviations) + "\n";
  }
  if (m.ape_M_se3) {
    out += format("  APE in M after SE(3) alignment: rmse %.3f m\n", m.ape_M_se3->rmse);
  }
  if (m.ape_odometry_from_true_start) {
    out += format("  odometry from the true start: APE rmse %.3f m\n",
                  m.ape_odometry_from_true_start->rmse);
  }
  for (const auto& note : m.notes) out += "  note: " + note + "\n";
  if (m.sim_seconds > 0) {
    out += format("  %.1f s of robot time in %.1f s: %.1fx real time\n", m.sim_seconds,
                  m.wall_seconds, m.real_time_factor);
  }
  return out;
}

}  // namespace isg::run
