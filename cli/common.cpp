#include "cli/common.hpp"

#include <charconv>
#include <cmath>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "bim/lidar_models.hpp"
#include "common/decimal_number.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {

bim::Scenario loadInput(const std::string& argument, const std::string& command) {
  common::Warnings warnings;
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin(argument, &warnings);
  for (const auto& w : warnings) std::cerr << "isg " << command << ": warning: " << w.str() << "\n";
  return scenario;
}

std::string inputFile(const std::string& argument) {
  return argument.rfind("builtin:", 0) == 0 ? std::string() : argument;
}

std::string builtinWorldsHelp() {
  std::string names;
  for (const auto& n : worlds::builtinNames()) names += (names.empty() ? "" : ", ") + n;
  return "PLAN|SCENARIO is a file in the isg.plan or isg.scenario format (docs/formats.md), or a "
         "built-in world written builtin:NAME, NAME one of: " +
         names + ".";
}

namespace {

CLI::Validator numberCheck(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        const std::optional<double> number = common::parseDecimal(text);
        if (!number) return "expected a number, got " + text;
        const double value = *number;
        if (allow_zero ? value < 0.0 : value <= 0.0) {
          return std::string(allow_zero ? "must be >= 0" : "must be > 0") + ", got " + text;
        }
        return "";
      },
      allow_zero ? "NUMBER >= 0" : "NUMBER > 0", allow_zero ? "non-negative" : "positive");
}

// A number as %g writes it: "0.0001", "10", "1e+07".
std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

CLI::Validator numberIn(double min, double max) {
  const std::string range = shortNumber(min) + " … " + shortNumber(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        const std::optional<double> value = common::parseDecimal(text);
        if (!value || *value < min || *value > max) {
          return "expected a number " + range + ", got " + text;
        }
        return "";
      },
      "NUMBER in [" + range + "]", "number in range");
}

void addLidarModelOption(CLI::App& app, std::string& model) {
  std::vector<std::string> names;
  for (const auto& m : bim::lidarModelDefaults()) names.push_back(m.name);
  app.add_option("--lidar", model,
                 "the LiDAR model instead of the scenario's, with its range gate, noise and "
                 "detection range (docs/simulation.md, \"LiDAR models\")")
      ->check(CLI::IsMember(names))
      ->option_text("MODEL")
      ->default_str("the scenario's (vlp16 unless it says)");
}

void useLidarModelOption(bim::Scenario& scenario, const std::string& model) {
  if (model.empty()) return;
  bim::useLidarModel(scenario.lidar, *bim::findLidarModelDefaults(model));
}

CLI::Validator seedNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        const auto [at, error] = std::from_chars(text.data(), end, value);
        if (!digits || error != std::errc() || at != end) {
          return "expected an integer 0 … 18446744073709551615, got " + text;
        }
        return "";
      },
      "SEED", "seed");
}

CLI::Validator positiveNumber() { return numberCheck(false); }
CLI::Validator nonNegativeNumber() { return numberCheck(true); }

}  // namespace isg::cli
