#pragma once

#include <nlohmann/json.hpp>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::bim {

// What planToJson writes beyond what an author must: a dataset records its plan with every
// default the parser fills in (the defaults), so that a replay compares plans field by field; a
// plan written for people (isg generate, isg import) leaves out what the parser fills in the
// same way.
struct PlanJsonStyle {
  // Each wall's height and base, even where they are its level's height and 0. Without: only
  // where they differ.
  bool every_wall_height = true;
  // Each door's two rooms, even where the parser inferred them from the outlines. Without: only
  // the rooms the file gave.
  bool inferred_door_rooms = true;
  // The names of levels, walls, openings and flights (where given) and where an imported plan
  // came from. Without: the geometry alone (how isg slam tells whether two plans are one).
  bool names = true;
};

// A plan as an "isg.plan" v1 document: the one writer of the plan format (datasets, isg import,
// isg generate, the test plans). Keys in the order docs/formats.md gives them; a room's name, a
// level's windows and stairs only where there are some. Parsing the result gives the same plan.
nlohmann::ordered_json planToJson(const Plan& plan, const PlanJsonStyle& style = {});

// What asBuiltToJson writes beyond what an author must. A dataset records every list and every
// field (what its run used); a scenario written for people (isg generate) gives only the lists
// that hold something, and an extra wall's base and level and a box's level only where they are
// not their defaults (0 m, the robot's level).
struct AsBuiltJsonStyle {
  bool empty_lists = true;
  bool default_fields = true;
};

// The as-built deviations as in a scenario's "as_built" object: the one writer of it (datasets,
// isg generate). Parsing the result (parseAsBuiltJson) gives the same deviations.
nlohmann::ordered_json asBuiltToJson(const AsBuilt& as_built, const AsBuiltJsonStyle& style = {});

}  // namespace isg::bim
