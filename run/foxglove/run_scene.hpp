#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "formats/ros_time.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// A run drawn in 3D as Foxglove scene entities (sensors/foxglove_json.hpp; docs/foxglove.md),
// from the run folder's JSON documents, so that a live run and a finished run folder draw the
// same. The graphs are drawn as in the S-Graphs papers: each layer above the storey it belongs
// to — walls (A-Graph) at kWallLayerHeight, rooms and doorways at kRoomLayerHeight, floors at
// kFloorLayerHeight — with the S-Graph's rooms and floors at the A-Graph's heights, so that a
// matched room sits on its plan room once the map is placed in the plan.
inline constexpr double kWallLayerHeight = 4.0;   // m above the storey's floor
inline constexpr double kRoomLayerHeight = 5.5;   // m
inline constexpr double kFloorLayerHeight = 7.0;  // m
inline constexpr double kPlaneDrawHeight = 2.5;   // m: an S-Graph wall plane's drawn height

// The plan from agraph.json, in frame "plan": entities "plan/walls" (every wall surface's
// segments as vertical faces over the surface's z range), "plan/doorways" (flat marks on the
// floor, the doorway's width along its wall), "plan/rooms" (outlines and names).
std::vector<nlohmann::json> planEntities(const nlohmann::json& agraph, formats::RosTime stamp);

// The A-Graph from agraph.json, in frame "plan": "agraph/nodes" (walls, rooms, doorways, floors
// at their layers; each wall surface at the top of its longest segment's middle) and
// "agraph/edges" (wall–surface, room–surface, doorway–room, floor–room).
std::vector<nlohmann::json> agraphEntities(const nlohmann::json& agraph, formats::RosTime stamp);

// The S-Graph from an sgraph.json document (the is-graphs and s-graph methods' graph()), in frame
// "map": "sgraph/keyframes", "sgraph/planes" (each plane's observed extent from its floor up
// kPlaneDrawHeight), "sgraph/rooms", "sgraph/floors", "sgraph/edges" (keyframe–plane, plane–room,
// room–floor).
// A graph without those lists (another method's) draws empty entities.
std::vector<nlohmann::json> sgraphEntities(const nlohmann::json& sgraph, formats::RosTime stamp);

// The matcher's last attempt (sgraph.json's matching.last_match), in frame "plan":
// "matching/candidates" — the S-Graph's wall planes on the matched level as each candidate
// B_T_M would place them, on that level's floor, the best in green and the others in orange, each
// labelled with its score. Where several candidates fit, they show where the map could be. Empty
// when the graph has no attempt.
std::vector<nlohmann::json> candidateEntities(const nlohmann::json& sgraph,
                                              const nlohmann::json& agraph, formats::RosTime stamp);

// The deviation report (a run's, or deviations.json read by run::readDeviationReport), in frame
// "plan": "deviations/walls" — each judged wall's planned line coloured by its status, the
// as-built segments that judged it, and a label for each deviating wall — and the extra walls;
// "deviations/columns" and "deviations/map-against-plan" when it has them; each level at its
// elevation in `agraph`.
std::vector<nlohmann::json> deviationEntities(const slam::DeviationReport& report,
                                              const nlohmann::json& agraph, formats::RosTime stamp);

}  // namespace isg::run
