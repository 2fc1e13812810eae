#include "slam/deviations/deviation_options.hpp"

#include <cmath>

namespace isg::slam {
namespace {

// Each check says whether the value is in range; NaN is in none (every comparison fails).
bool positive(double v) { return v > 0.0 && std::isfinite(v); }
bool nonNegative(double v) { return v >= 0.0 && std::isfinite(v); }
bool share(double v) { return v >= 0.0 && v <= 1.0; }
bool angleUpTo90(double v) { return v > 0.0 && v <= 90.0; }

}  // namespace

std::optional<std::string> DeviationOptions::invalidField() const {
  struct Check {
    const char* name;
    bool ok;
    const char* why;
  };
  const Check checks[] = {
      {"search_distance_m", positive(search_distance), "must be above 0"},
      {"search_angle_deg", angleUpTo90(search_angle_deg), "must lie in (0, 90]"},
      {"min_wall_length_m", nonNegative(min_wall_length), "must be 0 or more"},
      {"column_margin_m", nonNegative(column_margin), "must be 0 or more"},
      {"shift_m", positive(shift_m), "must be above 0"},
      {"angle_deg", angleUpTo90(angle_deg), "must lie in (0, 90]"},
      {"noise_factor", nonNegative(noise_factor), "must be 0 or more"},
      {"min_noise_walls", min_noise_walls >= 4,
       "must be at least 4 (the local placement fits 3 numbers on them)"},
      {"consistent_tolerance_m", positive(consistent_tolerance), "must be above 0"},
      {"contradiction_observation_share", share(contradiction_observation_share),
       "must lie in [0, 1]"},
      {"min_deviation_observations", min_deviation_observations >= 1, "must be at least 1"},
      {"min_angle_length_m", nonNegative(min_angle_length), "must be 0 or more"},
      {"judged_share", judged_share > 0.0 && judged_share <= 1.0, "must lie in (0, 1]"},
      {"missing_seen_share", missing_seen_share >= 0.0 && missing_seen_share <= judged_share,
       "must lie in [0, judged_share]"},
      {"missing_view_share", share(missing_view_share), "must lie in [0, 1]"},
      {"missing_sight_share", share(missing_sight_share), "must lie in [0, 1]"},
      {"min_missing_length_m", nonNegative(min_missing_length), "must be 0 or more"},
      {"view_range_m", positive(view_range), "must be above 0"},
      {"max_incidence_deg", angleUpTo90(max_incidence_deg), "must lie in (0, 90]"},
      {"min_views", min_views >= 1, "must be at least 1"},
      {"see_through_margin_m", nonNegative(see_through_margin), "must be 0 or more"},
      {"window_margin_m", nonNegative(window_margin), "must be 0 or more"},
      {"bend_distance_m", positive(bend_distance), "must be above 0"},
      {"bend_angle_deg", angleUpTo90(bend_angle_deg), "must lie in (0, 90]"},
      {"local_radius_m", positive(local_radius), "must be above 0"},
      {"extra_pair_distance_m", nonNegative(extra_pair_distance), "must be 0 or more"},
      {"max_stray_lean_deg", nonNegative(max_stray_lean_deg) && max_stray_lean_deg <= 90.0,
       "must lie in [0, 90]"},
      {"pivot_name_distance_m", nonNegative(pivot_name_distance), "must be 0 or more"},
      {"end_sigma_m", positive(end_sigma_m), "must be above 0"},
      {"clear_factor", nonNegative(clear_factor), "must be 0 or more"},
      {"progress_step_m", positive(progress_step), "must be above 0"},
      {"progress_gap_m", positive(progress_gap_m) && progress_gap_m >= progress_step,
       "must be at least progress_step_m"},
  };
  for (const Check& check : checks) {
    if (!check.ok) return std::string(check.name) + ": " + check.why;
  }
  return std::nullopt;
}

}  // namespace isg::slam
