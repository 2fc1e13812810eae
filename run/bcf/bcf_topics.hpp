#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bim/plan.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run::bcf {

// Where a topic's viewpoint looks from, in B (the plan's frame, which an IFC import keeps as the
// model's): a perspective camera above and in front of the element, looking 60° down at it with
// the ceilings off, so that the element and what stands around it are in view.
struct TopicCamera {
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double vertical_fov_deg = 60.0;
  double aspect = 4.0 / 3.0;  // width / height, the snapshot's too
  Eigen::Vector3d direction() const { return (target - eye).normalized(); }
  // Perpendicular to the direction, in the vertical plane through it, pointing up.
  Eigen::Vector3d up() const;
};

// A box outline in B: the element's planned footprint (or the extra wall's measured one) from
// `floor_z` to `top_z`, drawn in the snapshot and as the viewpoint's lines.
struct TopicOutline {
  std::vector<Eigen::Vector2d> footprint;  // in order, closed
  double floor_z = 0.0, top_z = 0.0;
  // Its edges as segments (from, to): the footprint's at the floor and at the top, and an upright
  // at each corner.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges() const;
};

// One BCF topic (docs/deviations.md, "BCF"): an element off the plan.
struct Topic {
  std::string guid;            // the topic's, lower-case UUID: its folder in the archive
  std::string viewpoint_guid;  // its one viewpoint's
  std::string element_kind;    // "wall", "column" or "extra wall"
  std::string element_id;      // the plan's id; "" for an extra wall
  std::string ifc_guid;        // the element's IFC GlobalId; "" when the plan has none
  std::string level;
  std::string title;
  std::string description;  // the verdict's numbers with their uncertainty and the tolerances
  // The verdict ("Shifted", "Turned", "Missing", "Not built", "Built in part", "Moved", "Extra"),
  // the scan-vs-BIM status, the kind of element and the level.
  std::vector<std::string> labels;
  TopicCamera camera;
  TopicOutline outline;
};

// What names the topics: the run's world (its content hash) and the run (method and seed). A
// topic's GUID is the element's in that world, the same in every run of it, so a BIM tool updates
// the topic a later run reports again; a viewpoint's GUID is the run's as well, as BCF's
// viewpoints never change once written.
struct TopicNames {
  std::string world_hash;
  std::string run;  // e.g. "is_graphs seed 1"
};
// A run's names: its world's content hash, or, for a replay (which has none), the plan's content
// hash; the run as method and seed.
TopicNames topicNames(const std::string& world_hash, const bim::Plan& plan,
                      const std::string& method, std::uint64_t seed);

// The report's topics in order: the plan's walls off the plan, missing, not built or built in
// part (one topic per wall, its worst verdict first), the columns moved or missing, then the
// extra walls. `plan` is the plan the report was measured against (its levels' elevations and
// heights, the elements' IFC GlobalIds).
std::vector<Topic> deviationTopics(const slam::DeviationReport& report, const bim::Plan& plan,
                                   const TopicNames& names);

// The topic types, statuses and labels the topics use, for the archive's extensions.xml.
std::vector<std::string> topicLabels();
inline constexpr const char* kTopicType = "Issue";
inline constexpr const char* kTopicStatus = "Open";

}  // namespace isg::run::bcf
