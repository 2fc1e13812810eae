#include "run/bcf/bcf_topics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "bim/column.hpp"
#include "bim/plan_json.hpp"
#include "common/content_hash.hpp"

namespace isg::run::bcf {

namespace {

// The namespace of every name-based UUID of the testbed's BCF (common::nameUuid); any fixed UUID
// will do, this one was drawn once at random.
constexpr const char* kBcfNamespace = "5d3f0a52-7c1e-4b8e-9a26-3f1c0e8b7d41";

// The scan-vs-BIM tools' words for what was found of an element.
constexpr const char* kOutOfTolerance = "Installed, out of tolerance";
constexpr const char* kNotFound = "Not found";
constexpr const char* kPartlyInstalled = "Partly installed";
constexpr const char* kNotInModel = "Not in the model";

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c, d);
  return text;
}

// The rectangle `thickness` wide about the segment start → end.
std::vector<Eigen::Vector2d> segmentFootprint(const Eigen::Vector2d& start,
                                              const Eigen::Vector2d& end, double thickness) {
  const Eigen::Vector2d along = (end - start).normalized();
  const Eigen::Vector2d half =
      0.5 * std::max(thickness, 0.05) * Eigen::Vector2d(-along.y(), along.x());
  return {start - half, end - half, end + half, start + half};
}

// Above and in front of the element (`towards`: the side to look from, in the plane), 60° down at
// its middle one metre above the floor, far enough for the whole footprint to be in view.
TopicCamera cameraAt(const TopicOutline& outline, Eigen::Vector2d towards) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& p : outline.footprint) box.extend(p);
  const Eigen::Vector2d centre = box.center();
  TopicCamera camera;
  const double half_width_fov =
      std::atan(std::tan(0.5 * camera.vertical_fov_deg * std::numbers::pi / 180.0) * camera.aspect);
  const double distance = std::max(6.0, 0.75 * box.diagonal().norm() / std::tan(half_width_fov));
  if (towards.norm() < 1e-9) towards = Eigen::Vector2d(0.0, -1.0);
  towards.normalize();
  // 60° down: the footprint on the floor shows beside the wall that stands off it.
  const double across = distance * 0.5, up = distance * std::sqrt(0.75);
  camera.target = Eigen::Vector3d(centre.x(), centre.y(), outline.floor_z + 1.0);
  camera.eye = camera.target + Eigen::Vector3d(towards.x() * across, towards.y() * across, up);
  return camera;
}

std::string levelWords(const std::string& level) { return " on level " + level; }

// The numbers of a wall seen off the plan: the offset and angle with their standard deviations
// (the placement's included) and the thresholds they were judged by.
std::string offPlanWords(const slam::WallDeviation& wall) {
  std::string words;
  if (wall.offset_m) {
    words += format(
        "Offset %+.3f m ± %.3f m (one standard deviation, the map's placement there included: "
        "%.3f m) from its planned place, along its left normal (positive to the left of start to "
        "end) at its centre; threshold %.3f m. ",
        *wall.offset_m, wall.offset_sigma_m.value_or(0.0), wall.placement_sigma_m,
        wall.shift_threshold_m);
  }
  if (wall.angle_deg) {
    words += format("Angle %+.2f° ± %.2f° (counter-clockwise positive), threshold %.2f°",
                    *wall.angle_deg, wall.angle_sigma_deg.value_or(0.0), wall.angle_threshold_deg);
    if (wall.pivot_along_m) {
      words += format(", turned about a point %.2f m ± %.2f m from its start (",
                      *wall.pivot_along_m, wall.pivot_sigma_m.value_or(0.0)) +
               wall.turned_about + ")";
    }
    words += ". ";
  }
  int keyframes = 0;
  for (const slam::WallEvidence& evidence : wall.evidence) {
    keyframes = std::max(keyframes, evidence.observations);
  }
  words += format("Seen over %.0f %% of its %.2f m, from up to %.0f keyframes.",
                  100.0 * wall.observed_share, (wall.planned_end - wall.planned_start).norm(),
                  double(keyframes));
  return words;
}

std::string progressWords(const slam::WallProgress& progress) {
  return format("Of its %.2f m to build: %.2f m standing, %.2f m not built, %.2f m not seen.",
                progress.planned_m, progress.built_m, progress.not_built_m, progress.not_seen_m);
}

struct WallVerdict {
  std::string title;
  std::vector<std::string> labels;
};

// A wall's topic title and labels, its worst verdict first; none when nothing is off.
std::optional<WallVerdict> wallVerdict(const slam::WallDeviation& wall) {
  WallVerdict verdict;
  const std::string name = "Wall " + wall.wall;
  using slam::ProgressStatus, slam::WallStatus;
  if (wall.status == WallStatus::kMissing) {
    verdict = {name + " missing", {"Missing", kNotFound}};
  } else if (wall.progress.status == ProgressStatus::kNotBuilt) {
    verdict = {name + " not built", {"Not built", kNotFound}};
  } else if (wall.status == WallStatus::kRotated) {
    verdict = {name + format(" turned %+.1f°", wall.angle_deg.value_or(0.0)),
               {"Turned", kOutOfTolerance}};
  } else if (wall.status == WallStatus::kShifted) {
    verdict = {name + format(" shifted %+.2f m", wall.offset_m.value_or(0.0)),
               {"Shifted", kOutOfTolerance}};
  }
  if (wall.progress.status == ProgressStatus::kPartlyBuilt) {
    if (verdict.title.empty()) verdict.title = name + " built in part";
    verdict.labels.push_back("Built in part");
    verdict.labels.push_back(kPartlyInstalled);
  }
  if (verdict.title.empty()) return std::nullopt;
  verdict.labels.push_back("Wall");
  return verdict;
}

void nameTopic(Topic& topic, const TopicNames& names, const std::string& element) {
  const std::string key = names.world_hash + "/" + topic.level + "/" + element;
  topic.guid = common::nameUuid(kBcfNamespace, key);
  topic.viewpoint_guid = common::nameUuid(kBcfNamespace, key + "/viewpoint/" + names.run);
}

// A topic about the plan's element `id` of `kind` on `level`, selected by its GlobalId (if any).
Topic elementTopic(const char* kind, const std::string& id, const std::string& ifc_guid,
                   const std::string& level) {
  Topic topic;
  topic.element_kind = kind;
  topic.element_id = id;
  topic.ifc_guid = ifc_guid;
  topic.level = level;
  return topic;
}

std::optional<Topic> wallTopic(const slam::WallDeviation& wall, const bim::Plan& plan,
                               const TopicNames& names) {
  const auto verdict = wallVerdict(wall);
  if (!verdict) return std::nullopt;
  const bim::Level* level = plan.findLevel(wall.level);
  const bim::Wall* planned = level ? level->findWall(wall.wall) : nullptr;
  Topic topic =
      elementTopic("wall", wall.wall, planned ? planned->ifc_guid : wall.ifc_guid, wall.level);
  topic.title = verdict->title;
  topic.labels = verdict->labels;
  topic.description = topic.title + levelWords(wall.level) + ". ";
  if (wall.status == slam::WallStatus::kShifted || wall.status == slam::WallStatus::kRotated) {
    topic.description += offPlanWords(wall) + " ";
  }
  topic.description += progressWords(wall.progress);
  const double elevation = level ? level->elevation : 0.0;
  const double height =
      planned && planned->height > 0.0 ? planned->height : (level ? level->height : 2.5);
  topic.outline = {segmentFootprint(wall.planned_start, wall.planned_end, wall.thickness),
                   elevation + (planned ? planned->base : 0.0), elevation + height};
  const Eigen::Vector2d along = (wall.planned_end - wall.planned_start).normalized();
  const int side = wall.evidence.empty() ? +1 : wall.evidence.front().side;
  topic.camera = cameraAt(topic.outline, side * Eigen::Vector2d(-along.y(), along.x()));
  nameTopic(topic, names, "wall/" + wall.wall);
  return topic;
}

std::optional<Topic> columnTopic(const slam::ColumnDeviation& column, const bim::Plan& plan,
                                 const TopicNames& names) {
  if (column.status != slam::ColumnStatus::kMoved &&
      column.status != slam::ColumnStatus::kMissing) {
    return std::nullopt;
  }
  const bim::Level* level = plan.findLevel(column.level);
  const bim::Column* planned = level ? level->findColumn(column.column) : nullptr;
  Topic topic = elementTopic("column", column.column, planned ? planned->ifc_guid : column.ifc_guid,
                             column.level);
  const bool moved = column.status == slam::ColumnStatus::kMoved;
  topic.title = "Column " + column.column + (moved ? " moved" : " missing");
  topic.labels = {moved ? "Moved" : "Missing", moved ? kOutOfTolerance : kNotFound, "Column"};
  topic.description = topic.title + levelWords(column.level) + ". ";
  if (column.offset_m) {
    topic.description += format(
        "Stands %+.3f m in x and %+.3f m in y of the plan from its "
        "planned centre (measured along %.0f of the two directions). ",
        column.offset_m->x(), column.offset_m->y(), double(column.directions_measured));
  }
  topic.description += format("%.0f points of the map on its outline; %.0f places saw past it.",
                              double(column.points), double(column.seen_past));
  const double elevation = level ? level->elevation : 0.0;
  topic.outline.footprint = planned ? bim::columnFootprint(*planned, 12) : column.planned_outline;
  if (topic.outline.footprint.empty()) {
    topic.outline.footprint =
        segmentFootprint(column.planned_centre - Eigen::Vector2d(0.2, 0.0),
                         column.planned_centre + Eigen::Vector2d(0.2, 0.0), 0.4);
  }
  topic.outline.floor_z = elevation + (planned ? planned->base : 0.0);
  topic.outline.top_z = elevation + (planned ? planned->height : (level ? level->height : 2.5));
  topic.camera = cameraAt(topic.outline, Eigen::Vector2d(0.0, -1.0));
  nameTopic(topic, names, "column/" + column.column);
  return topic;
}

Topic extraTopic(const slam::ExtraWall& extra, int index, const bim::Plan& plan,
                 const TopicNames& names) {
  const bim::Level* level = plan.findLevel(extra.level);
  Topic topic = elementTopic("extra wall", "", "", extra.level);
  topic.title = format("Extra wall %.0f, %.2f m long", double(index + 1), extra.length());
  topic.labels = {"Extra", kNotInModel, "Extra wall"};
  topic.description = "A wall the map has and the plan lacks" + levelWords(extra.level) +
                      format(": from (%.3f, %.3f) to (%.3f, %.3f) in the plan's frame, ",
                             extra.start.x(), extra.start.y(), extra.end.x(), extra.end.y()) +
                      format("%.2f m long, from %.0f of the map's wall faces.", extra.length(),
                             double(extra.planes.size()));
  const double elevation = level ? level->elevation : 0.0;
  topic.outline = {segmentFootprint(extra.start, extra.end, 0.1), elevation,
                   elevation + (level ? level->height : 2.5)};
  const Eigen::Vector2d along = (extra.end - extra.start).normalized();
  topic.camera = cameraAt(topic.outline, Eigen::Vector2d(-along.y(), along.x()));
  // An extra wall has no id: it is named by where it lies, to the decimetre.
  nameTopic(topic, names,
            format("extra/%.1f,%.1f,%.1f,%.1f", extra.start.x(), extra.start.y(), extra.end.x(),
                   extra.end.y()));
  return topic;
}

}  // namespace

std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> TopicOutline::edges() const {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges;
  const std::size_t n = footprint.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = footprint[i];
    const Eigen::Vector2d& q = footprint[(i + 1) % n];
    for (const double z : {floor_z, top_z}) edges.push_back({{p.x(), p.y(), z}, {q.x(), q.y(), z}});
    edges.push_back({{p.x(), p.y(), floor_z}, {p.x(), p.y(), top_z}});
  }
  return edges;
}

TopicNames topicNames(const std::string& world_hash, const bim::Plan& plan,
                      const std::string& method, std::uint64_t seed) {
  return {world_hash.empty() ? common::contentHash(bim::planToJson(plan).dump()) : world_hash,
          method + " seed " + std::to_string(seed)};
}

Eigen::Vector3d TopicCamera::up() const {
  const Eigen::Vector3d forward = direction();
  const Eigen::Vector3d side = forward.cross(Eigen::Vector3d::UnitZ());
  if (side.norm() < 1e-9) return Eigen::Vector3d::UnitY();
  return side.cross(forward).normalized();
}

std::vector<Topic> deviationTopics(const slam::DeviationReport& report, const bim::Plan& plan,
                                   const TopicNames& names) {
  std::vector<Topic> topics;
  for (const slam::WallDeviation& wall : report.walls) {
    if (auto topic = wallTopic(wall, plan, names)) topics.push_back(std::move(*topic));
  }
  for (const slam::ColumnDeviation& column : report.columns) {
    if (auto topic = columnTopic(column, plan, names)) topics.push_back(std::move(*topic));
  }
  for (std::size_t i = 0; i < report.extra_walls.size(); ++i) {
    topics.push_back(extraTopic(report.extra_walls[i], int(i), plan, names));
  }
  // Two extra walls within a decimetre of each other would share a name: the later ones are
  // told apart by their place in the report.
  std::set<std::string> taken;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    if (taken.insert(topics[i].guid).second) continue;
    nameTopic(topics[i], names, topics[i].guid + "#" + std::to_string(i));
    taken.insert(topics[i].guid);
  }
  return topics;
}

std::vector<std::string> topicLabels() {
  return {"Shifted",   "Turned", "Missing",       "Not built", "Built in part",
          "Moved",     "Extra",  kOutOfTolerance, kNotFound,   kPartlyInstalled,
          kNotInModel, "Wall",   "Column",        "Extra wall"};
}

}  // namespace isg::run::bcf
