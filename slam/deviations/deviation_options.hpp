#pragma once

#include <optional>
#include <string>

namespace isg::slam {

// As built against as planned (docs/deviations.md): once a map is placed in the plan, each plan
// wall of the levels the robot walked is compared with the map's walls in front of it. Every
// threshold is stated here and written to deviations.json with the report.
struct DeviationOptions {
  // A map wall is evidence for a plan surface facing the same way (normals within this angle)
  // when some point of it (an end or its middle) lies within `search_distance` of the surface's
  // plane and a third of it lies along the planned wall. Farther, it is an extra wall.
  double search_distance = 0.5;  // m
  double search_angle_deg = 20.0;
  double min_wall_length = 0.5;  // m: shorter map walls are not evidence
  // A map wall within this of a rectangular column's outline, all along, is a face of the column
  // (judged with the columns, slam::ColumnOptions::search_m alike), not an extra wall.
  double column_margin = 0.35;  // m
  // Judged deviating at or beyond these. Below them lies what the map's own noise explains: a
  // plane's offset to about 1 cm, its direction to a few tenths of a degree, the map's place in
  // the plan to 1–3 cm (docs/deviations.md, "Thresholds").
  double shift_m = 0.06;
  double angle_deg = 1.5;
  // Where the map is worse, so is the evidence: a wall is judged against the larger of those and
  // `noise_factor` times the map's own error around it — the length-weighted RMS of the offsets
  // (and, over walls at least min_angle_length long, the angles) the walls found as planned
  // within local_radius keep once the local placement is applied, scaled by √(n/(n−3)) for the
  // three numbers that placement fitted on their n walls (none with fewer than `min_noise_walls`).
  // Three times a normal error is passed by chance once in 370 walls. With fewer walls around,
  // the local placement rests on one or two of them and their own error moves it: a deviation
  // is then believed only when the level's placement (on all its walls) finds it too. The shift
  // threshold is also at least `noise_factor` times how well those walls fix the map across the
  // wall (the local placement's standard deviation along its normal: WallDeviation::
  // placement_sigma_m; the placement's 5 cm prior where none of them does).
  double noise_factor = 3.0;
  int min_noise_walls = 5;
  // A wall's evidence is consistent when both ends of a piece lie within this of the line its
  // pieces fit (the longest first); the others (a plane fitted across a corner, a door leaf)
  // are kept as evidence and not believed.
  double consistent_tolerance = 0.04;  // m
  // A long piece left out of that fit (at least half as long as the longest piece kept) makes
  // the wall's evidence contradict itself (two faces laid by the map a few cm apart) only when it
  // was observed at least this share as often as the most observed piece kept: a plane seen on
  // a keyframe or two, across a wall turned off the building's axes, is a stray fit, not a face.
  double contradiction_observation_share = 0.25;
  // A wall is called shifted or turned only when a piece of its consistent evidence was observed
  // from at least this many keyframes; a deviation seen on fewer is not believed and the wall is
  // `not_seen` (seen too little to judge). The plan is the prior: on the generated sites a plane
  // seen once or twice along a façade bay (a pallet's side before it, a glance across a corner)
  // was 5 of the 6 walls falsely reported off, while every one of the 148 walls reported off on
  // the office suites (all but one truly) was seen on 4 keyframes or more (docs/deviations.md,
  // "Statuses and thresholds").
  int min_deviation_observations = 3;
  // A direction is judged only from a map wall at least this long: a short plane's direction is
  // too loose to call a wall turned.
  double min_angle_length = 1.0;  // m
  // A wall is judged when its evidence covers this share of its length; less is `not_seen`, or
  // `missing` when next to nothing of it was seen (below `missing_seen_share`) though it lay in
  // the sensor's view over `missing_view_share` of its length.
  double judged_share = 0.2;
  double missing_seen_share = 0.05;
  double missing_view_share = 0.6;
  // When the keyframes recorded how far they saw (SightProfile), "in view" is "seen past": the
  // evidence of absence itself, which a wall standing there denies along every sight line it
  // stops. Near the wall's ends the sight lines past it meet the walls it joins within the margin,
  // so a missing wall between two offices is seen past over 55–60 % of its faces where geometry
  // had 60–70 % in view: this share stands for missing_view_share then.
  double missing_sight_share = 0.4;
  double min_missing_length = 1.0;  // m: a shorter wall is never called missing
  // In view: a point of a face within `view_range` of at least `min_views` keyframes standing in
  // front of it, at most `max_incidence_deg` off its normal, that saw past it: their farthest
  // return toward it lies beyond the wall's far face by `see_through_margin` (the map's place in
  // the plan to a few cm, a return's degree of azimuth 14 cm wide at view_range). Keyframes that
  // did not record how far they saw count when no other plan wall lies between.
  double view_range = 8.0;  // m
  double max_incidence_deg = 60.0;
  int min_views = 3;
  // The same margin tells a sight line blocked by a map wall (seenOnlyThroughWalls, for extra
  // walls seen from fewer than min_deviation_observations keyframes).
  double see_through_margin = 0.2;  // m
  // A wall's windows, widened by this each side (a degree of azimuth at view_range), are seen
  // through whether the wall stands or not: there only the map's walls say it is built.
  double window_margin = 0.15;  // m
  // A wall is placed by the final B_T_M unless the robot's poses in B when it saw the wall put
  // it farther than this from there (the map has bent since): then by those poses.
  double bend_distance = 0.05;  // m
  double bend_angle_deg = 0.5;
  // Each wall is measured after a placement fitted on the walls within this distance of it (and
  // not itself): the map bends a little over a long building.
  double local_radius = 6.0;  // m
  // Two opposite faces of extra walls at most this far apart are one wall.
  double extra_pair_distance = 0.4;  // m
  // A map wall seen from fewer than min_deviation_observations keyframes whose plane leans more
  // than this off vertical is a stray fit, not an extra wall: walls stand plumb, and a plane
  // fitted once from a keyframe whose attitude was off leans with it. On the four suites every
  // extra wall seen 3 times or more leaned at most 0.46°; the six seen once that leaned 1.0–2.7°
  // stood where nothing is (docs/deviations.md, "Extra walls").
  double max_stray_lean_deg = 1.0;
  // A turned wall's pivot (where its line crosses the planned axis) is named its start, centre or
  // end within this distance of it; elsewhere on the wall it is "along", off it "beyond" (a turn
  // and a shift together). The pivot is as loose as the offset over tan(angle): 1 cm of offset
  // at 2° moves it 0.29 m.
  double pivot_name_distance = 0.3;  // m
  // Each verdict carries its uncertainty (docs/deviations.md, "Uncertainty"): the fitted line's
  // offset and direction from the ends of its consistent pieces, each end taken to lie on the
  // wall's face to `end_sigma_m` (or to how far the ends scatter about the line, when they scatter
  // more), weighted by length as the fit weights them, with the local placement's own standard
  // deviations. A map wall's plane is fitted from hundreds of points to millimetres; its ends sit
  // where the keyframes that saw it put them, to about a centimetre. A wall is shifted (turned)
  // only when its offset (angle) lies `clear_factor` standard deviations from zero as well as at
  // or beyond its threshold; beyond the threshold but not clear of its uncertainty, the evidence
  // cannot tell, and the wall is `not_seen` (the scan-vs-BIM tools' "not enough data").
  double end_sigma_m = 0.01;
  double clear_factor = 2.0;
  // Progress (docs/deviations.md, "Progress"): each wall's exposed length sampled every
  // `progress_step`; a part in view with no map wall on it is not built when at least
  // `progress_gap_m` long. Shorter, the map cannot tell: a plane needs 100 voxels of 10 cm
  // (PlaneExtractionOptions::min_inliers), 0.4 m of a wall seen 2.5 m high, and a stretch between
  // a door and a wall meeting this one is found as a piece of its own or not at all. It stays
  // above the map's unconfirmed edge (ConfirmationOptions::near_m).
  double progress_step = 0.05;  // m
  double progress_gap_m = 0.6;  // m

  // The first field out of its range, as "name: why" (the name as deviations.json's thresholds
  // give it); nullopt when every field is in range. measureDeviations refuses options that are
  // not (std::invalid_argument with this text).
  std::optional<std::string> invalidField() const;
  bool isValid() const { return !invalidField(); }
};

}  // namespace isg::slam
