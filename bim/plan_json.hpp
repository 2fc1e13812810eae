#pragma once

#include <nlohmann/json.hpp>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::bim {

// A parsed plan written back as an "isg.plan" v1 document, with every default filled in (door
// rooms included): what a dataset records as the plan it was made from. Parsing the result gives
// the same plan.
nlohmann::ordered_json planToJson(const Plan& plan);

// The as-built deviations as in a scenario's "as_built" object.
nlohmann::ordered_json asBuiltToJson(const AsBuilt& as_built);

}  // namespace isg::bim
