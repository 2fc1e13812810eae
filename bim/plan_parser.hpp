#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bim/plan.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {

inline constexpr const char* kPlanFormat = "isg.plan";
inline constexpr int kPlanVersion = 1;

// Parses and validates a plan ("isg.plan" v1, docs/formats.md). Every rule of docs/formats.md is
// checked; the first violation throws an InputError naming the file, the JSON pointer and the
// reason. Defaults are filled, clockwise outlines are turned counter-clockwise (with a warning),
// and doors without "rooms" get them inferred from the outlines.
Plan parsePlan(const common::JsonNode& root);

// Reads a plan file. Warnings (unknown fields, ...) are appended to `warnings` when given.
Plan loadPlan(const std::string& path, common::Warnings* warnings = nullptr);

}  // namespace isg::bim
