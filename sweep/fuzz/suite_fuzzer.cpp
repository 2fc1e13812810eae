// libFuzzer harness: bytes → the suite reader of `isg sweep` (with every generator spec checked by
// building it, as the reader does), then the cells and the sweep.json text a sweep would write,
// read back. An InputError from the reader is the expected answer to a bad suite; anything else
// (a crash, a sanitizer report, an exception after the suite was accepted) is a bug.
//
// Bound of the harness, not of the reader: a suite asking for more than kMostRooms offices in all
// is skipped, because building large generated worlds is legitimately slow (0.5–1 s for 5000
// offices, several times that under the sanitizers: cli_bench and docs/sweeps.md measure it) and
// would read as a libFuzzer timeout. Relative world files resolve against the working folder.
#include <cstdint>
#include <optional>
#include <string>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "run/builtin_methods.hpp"
#include "sweep/suite.hpp"

namespace {

constexpr std::uint64_t kMostRooms = 2000;
constexpr std::uint64_t kMostCells = 20000;

// Offices the suite's generator specs ask for, counted as the reader will build them: the first
// building of each spec, with its room count or the family's default (under 40).
std::uint64_t roomsAskedFor(const nlohmann::json& suite) {
  std::uint64_t rooms = 0;
  if (!suite.is_object() || !suite.contains("worlds") || !suite["worlds"].is_array()) return 0;
  for (const auto& world : suite["worlds"]) {
    if (!world.is_object() || !world.contains("generate")) continue;
    const auto& spec = world["generate"];
    rooms += 40;
    if (spec.is_object() && spec.contains("rooms") && spec["rooms"].is_number()) {
      const double asked = spec["rooms"].get<double>();
      if (asked > 0) rooms += asked < 1e9 ? std::uint64_t(asked) : std::uint64_t(1e9);
    }
    if (spec.is_object() && spec.contains("partitions") && spec["partitions"].is_number()) {
      rooms += 10;  // a hall filled with partitions costs as much as some more rooms
    }
  }
  return rooms;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace isg;
  static const run::LocalizerRegistry methods = run::builtinMethods();
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<sweep::Suite> suite;
  try {
    const nlohmann::json document = common::parseJsonText(text, "fuzz.json");
    if (roomsAskedFor(document) > kMostRooms) return 0;
    const common::JsonSource source{"fuzz.json", nullptr};
    suite = sweep::parseSuite(common::JsonNode(document, "", source), "fuzz.json", methods);
  } catch (const common::InputError&) {
    return 0;
  }
  if (suite->worlds.size() * suite->methods.size() * suite->seeds.size() > kMostCells) return 0;
  // From here on nothing may throw: sweep.json as a sweep writes it must read back, as a
  // restarted sweep reads it, to the same cells.
  const std::vector<sweep::SweepCell> cells = sweep::sweepCells(*suite);
  const nlohmann::json written =
      common::parseJsonText(sweep::sweepPlanJson(*suite, cells), "sweep.json");
  const common::JsonSource plan_source{"sweep.json", nullptr};
  const sweep::SweepPlan plan = sweep::parseSweepPlan(common::JsonNode(written, "", plan_source));
  if (plan.cells.size() != cells.size()) __builtin_trap();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (plan.cells[i].dir != cells[i].dir || plan.cells[i].arguments != cells[i].arguments) {
      __builtin_trap();  // a restarted sweep would refuse its own folder
    }
  }
  return 0;
}
