#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bim/agraph.hpp"

namespace isg::bim {

// The A-Graph as the documented JSON of docs/agraph.md ("format": "isg.agraph", version 1).
nlohmann::ordered_json agraphToJson(const AGraph& graph);

// The text of that JSON for people and diffs: one node or edge per line.
std::string agraphJsonText(const nlohmann::ordered_json& document);

}  // namespace isg::bim
