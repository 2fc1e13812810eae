#include "slam/deviations/wall_progress.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "slam/deviations/face_views.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::slam {

namespace {

// Intervals in order with the overlapping and touching ones joined.
Intervals joined(Intervals spans) {
  std::sort(spans.begin(), spans.end());
  Intervals out;
  for (const auto& [a, b] : spans) {
    if (b <= a) continue;
    if (!out.empty() && a <= out.back().second) {
      out.back().second = std::max(out.back().second, b);
    } else {
      out.push_back({a, b});
    }
  }
  return out;
}

// `spans` less `holes` (both in order).
Intervals without(const Intervals& spans, const Intervals& holes) {
  Intervals out;
  for (auto [a, b] : spans) {
    for (const auto& [h0, h1] : holes) {
      if (h1 <= a || h0 >= b) continue;
      if (h0 > a) out.push_back({a, h0});
      a = std::max(a, h1);
      if (a >= b) break;
    }
    if (a < b) out.push_back({a, b});
  }
  return out;
}

// The interval of `spans` that holds s, if one does.
std::optional<std::pair<double, double>> within(const Intervals& spans, double s) {
  for (const auto& span : spans) {
    if (s >= span.first && s <= span.second) return span;
  }
  return std::nullopt;
}

bool inside(const Intervals& spans, double s) { return within(spans, s).has_value(); }

enum class Sample { kBuilt, kNotBuilt, kNotSeen };
using Samples = std::vector<std::pair<double, Sample>>;  // (s along the axis, what it is)

// One face of the wall and its exposed parts along the axis.
struct Face {
  Intervals exposed;
  Eigen::Vector2d normal, offset;  // the face's outward normal; the face from the axis
};

// Each face's exposed parts along the axis, door openings left out (nothing is built there as
// planned); `exposed` gets both faces' together.
std::vector<Face> exposedFaces(const bim::AGraph& plan, const bim::WallNode& wall,
                               const Eigen::Vector2d& start, const Eigen::Vector2d& axis,
                               double length, Intervals& exposed) {
  std::vector<Face> faces;
  Intervals all_exposed;
  for (int surface : {wall.left_surface, wall.right_surface}) {
    const bim::WallSurfaceNode& node = plan.surfaces[surface];
    Face face;
    face.normal = node.plane.normal.head<2>().normalized();
    face.offset = 0.5 * wall.thickness * face.normal;
    for (const auto& [a, b] : node.segments) {
      double s0 = (a - start).dot(axis), s1 = (b - start).dot(axis);
      if (s0 > s1) std::swap(s0, s1);
      face.exposed.push_back({std::clamp(s0, 0.0, length), std::clamp(s1, 0.0, length)});
    }
    face.exposed = joined(face.exposed);
    all_exposed.insert(all_exposed.end(), face.exposed.begin(), face.exposed.end());
    faces.push_back(face);
  }
  Intervals doors;
  for (const auto& door : plan.doorways) {
    if (door.wall != wall.id) continue;
    const double c = (door.position.head<2>() - start).dot(axis);
    doors.push_back({c - 0.5 * door.width, c + 0.5 * door.width});
  }
  doors = joined(doors);
  for (Face& face : faces) face.exposed = without(face.exposed, doors);
  exposed = without(joined(all_exposed), doors);
  return faces;
}

// A run not built shorter than progress_gap_m between built parts is the map's own ragged edge,
// not a gap: built.
void bridgeRaggedEdges(Samples& samples, double step, double gap_m) {
  for (std::size_t i = 0; i < samples.size();) {
    if (samples[i].second != Sample::kNotBuilt) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < samples.size() && samples[j].second == Sample::kNotBuilt) ++j;
    const bool between = i > 0 && j < samples.size() && samples[i - 1].second == Sample::kBuilt &&
                         samples[j].second == Sample::kBuilt;
    if (between && samples[j].first - samples[i - 1].first - step < gap_m) {
      for (std::size_t k = i; k < j; ++k) samples[k].second = Sample::kBuilt;
    }
    i = j;
  }
}

// The built part around built sample i: its step, or beside a sample that is not built, to where
// the evidence ends, somewhere between the two samples, not at the boundary between their steps
// (that would put each edge of a gap up to half a step off, and a wall's built length a step off).
std::pair<double, double> builtAround(const Samples& samples, std::size_t i,
                                      const Intervals& built_evidence, double step, double length,
                                      bool after_opening) {
  double from = std::max(0.0, samples[i].first - 0.5 * step);
  double to = std::min(length, samples[i].first + 0.5 * step);
  const std::optional<std::pair<double, double>> covering =
      within(built_evidence, samples[i].first);
  if (covering && i > 0 && !after_opening && samples[i - 1].second != Sample::kBuilt) {
    from = std::clamp(covering->first, samples[i - 1].first, samples[i].first);
  }
  if (covering && i + 1 < samples.size() && samples[i + 1].second != Sample::kBuilt &&
      samples[i + 1].first - samples[i].first <= 1.5 * step) {
    to = std::clamp(covering->second, samples[i].first, samples[i + 1].first);
  }
  return {from, to};
}

// The built parts (progress.built) and the length not built (progress.not_built_m) from the
// samples, each `weight` long; returns the longest run not built.
double collectBuiltParts(const Samples& samples, const Intervals& built_evidence, double length,
                         double weight, const DeviationOptions& options, WallProgress& progress) {
  const double step = options.progress_step;
  double longest_gap = 0.0, run = 0.0;
  bool not_built_between = false;  // since the last built sample
  double unseen_between = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample kind = samples[i].second;
    not_built_between = not_built_between || kind == Sample::kNotBuilt;
    if (kind == Sample::kNotSeen) unseen_between += weight;
    if (kind == Sample::kNotBuilt) progress.not_built_m += weight;
    // A run not built ends at a door opening (not sampled): the stretches either side of a door
    // are each as short as they are.
    const bool after_opening = i > 0 && samples[i].first - samples[i - 1].first > 1.5 * step;
    run = kind == Sample::kNotBuilt ? (after_opening ? 0.0 : run) + weight : 0.0;
    longest_gap = std::max(longest_gap, run);
    if (kind != Sample::kBuilt) continue;
    // Built runs, bridged across what lies between two built parts shorter than progress_gap_m
    // and not in view (a door opening, not exposed and not sampled; the end of a wall meeting
    // this one): the wall goes on there.
    const auto [from, to] = builtAround(samples, i, built_evidence, step, length, after_opening);
    if (!progress.built.empty() && unseen_between < options.progress_gap_m && !not_built_between) {
      progress.built.back().second = to;
    } else {
      progress.built.push_back({from, to});
    }
    not_built_between = false;
    unseen_between = 0.0;
  }
  return longest_gap;
}

// A built part stands to the wall's end when only a stretch out of view, shorter than
// progress_gap_m, lies between (the end inside a wall meeting this one, its outer face never in
// view): nothing says it stops short.
void builtToTheEnds(const Samples& samples, double length, double gap_m, WallProgress& progress) {
  if (progress.built.empty()) return;
  const auto first_built = std::find_if(samples.begin(), samples.end(),
                                        [](const auto& x) { return x.second == Sample::kBuilt; });
  const auto last_built = std::find_if(samples.rbegin(), samples.rend(),
                                       [](const auto& x) { return x.second == Sample::kBuilt; });
  const auto not_built = [](const auto& x) { return x.second == Sample::kNotBuilt; };
  if (progress.built.front().first < gap_m &&
      std::none_of(samples.begin(), first_built, not_built)) {
    progress.built.front().first = 0.0;
  }
  if (length - progress.built.back().second < gap_m &&
      std::none_of(samples.rbegin(), last_built, not_built)) {
    progress.built.back().second = length;
  }
}

// The status, from what was seen of the planned length and the longest run not built.
ProgressStatus progressStatus(const WallProgress& progress, double longest_gap,
                              const DeviationOptions& options) {
  const double seen = progress.built_m + progress.not_built_m;
  if (seen < options.judged_share * progress.planned_m) return ProgressStatus::kNotSeen;
  if (longest_gap < options.progress_gap_m) return ProgressStatus::kBuilt;
  if (progress.built_m < options.missing_seen_share * progress.planned_m)
    return ProgressStatus::kNotBuilt;
  return ProgressStatus::kPartlyBuilt;
}

}  // namespace

const char* toString(ProgressStatus status) {
  switch (status) {
    case ProgressStatus::kBuilt:
      return "built";
    case ProgressStatus::kPartlyBuilt:
      return "partly_built";
    case ProgressStatus::kNotBuilt:
      return "not_built";
    case ProgressStatus::kNotSeen:
      break;
  }
  return "not_seen";
}

double overlapLength(const Intervals& a, const Intervals& b) {
  double total = 0.0;
  for (const auto& [a0, a1] : a) {
    for (const auto& [b0, b1] : b) total += std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
  }
  return total;
}

WallProgress measureProgress(const bim::AGraph& plan, const bim::WallNode& wall,
                             const Eigen::Vector2d& start, const Eigen::Vector2d& axis,
                             double length, const Intervals& evidence,
                             const std::vector<Viewpoint>& viewpoints,
                             const DeviationOptions& options, const BuiltLine& built) {
  WallProgress progress;
  const std::vector<Face> faces = exposedFaces(plan, wall, start, axis, length, progress.exposed);
  const Intervals built_evidence = joined(evidence);
  // Each sample of the exposed length: built where the evidence covers it; else not built where a
  // face of it was in view (seen past); else not seen. Views are asked only where nothing stands,
  // and not at windows (seen through, built or not).
  const double step = options.progress_step;
  const FaceViews views(plan, wall, viewpoints, options, built);
  const Intervals windows = joined(windowSpans(plan, wall, start, axis, options.window_margin));
  Samples samples;
  for (const auto& [a, b] : progress.exposed) {
    const int n = std::max(1, int(std::lround((b - a) / step)));
    for (int i = 0; i < n; ++i) {
      const double s = a + (i + 0.5) * (b - a) / n;
      Sample kind = Sample::kNotSeen;
      if (inside(built_evidence, s)) {
        kind = Sample::kBuilt;
      } else if (!inside(windows, s)) {
        for (const Face& face : faces) {
          if (inside(face.exposed, s) &&
              views.inView(start + s * axis + face.offset, face.normal)) {
            kind = Sample::kNotBuilt;
            break;
          }
        }
      }
      samples.push_back({s, kind});
    }
    progress.planned_m += b - a;
  }
  if (samples.empty()) return progress;
  const double weight = progress.planned_m / double(samples.size());
  bridgeRaggedEdges(samples, step, options.progress_gap_m);
  const double longest_gap =
      collectBuiltParts(samples, built_evidence, length, weight, options, progress);
  builtToTheEnds(samples, length, options.progress_gap_m, progress);
  // Built: the built parts over the exposed length, the junctions and short stretches out of view
  // they bridge included; not seen: the rest that is neither.
  progress.built_m = overlapLength(progress.built, progress.exposed);
  progress.not_seen_m = std::max(0.0, progress.planned_m - progress.built_m - progress.not_built_m);
  progress.status = progressStatus(progress, longest_gap, options);
  return progress;
}

}  // namespace isg::slam
