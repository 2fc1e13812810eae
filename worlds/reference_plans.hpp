#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bim/scenario.hpp"
#include "common/input_error.hpp"

namespace isg::worlds {

// The reference plans (worlds/plans/d1.json … d6.json) and their as-built scenarios
// (d1.asbuilt.json …) are compiled in, so `isg` runs them from anywhere. On the command line a
// built-in is written "builtin:d1" or "builtin:d1.asbuilt".
inline constexpr std::string_view kBuiltinPrefix = "builtin:";
// The world the main job runs when it is given none.
inline constexpr std::string_view kDefaultWorld = "builtin:d1.asbuilt";

// The names of the built-in files, without ".json": d1, d1.asbuilt, d2, ...
std::vector<std::string> builtinNames();

// The text of a built-in file, by name with or without ".json"; nullopt when there is none.
std::optional<std::string_view> builtinText(std::string_view name);

bool isBuiltin(std::string_view argument);

// A world's short name, for folder names and table rows: "builtin:d1.asbuilt" → "d1.asbuilt",
// "plans/office.asbuilt.json" → "office.asbuilt".
std::string worldName(const std::string& argument);

// Loads a scenario (or bare plan) from a file path, or from a built-in ("builtin:NAME"), whose
// plan reference resolves among the built-ins. Errors are InputErrors as for files. A replayed
// walk's crossed walls and columns are taken as the route says (worlds::takeCrossedSolids).
bim::Scenario loadScenarioOrBuiltin(const std::string& argument, common::Warnings* warnings);

}  // namespace isg::worlds
