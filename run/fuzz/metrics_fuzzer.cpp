// libFuzzer harness: bytes → metrics.json's reader (what isg table and isg sweep read from every
// run folder), and an accepted document written back and read again to the same JSON; every
// measure finite, and the errors and times >= 0.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "common/input_error.hpp"
#include "run/run_metrics.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
  if (document.is_discarded()) return 0;
  isg::run::RunMetrics metrics;
  try {
    metrics = isg::run::metricsFromJson(document, "fuzz/metrics.json");
  } catch (const isg::common::InputError&) {
    return 0;
  }
  if (metrics.ape_B && (!std::isfinite(metrics.ape_B->rmse) || metrics.ape_B->rmse < 0)) {
    std::abort();
  }
  if (metrics.time_to_localize && !(*metrics.time_to_localize >= 0)) std::abort();
  const nlohmann::json written = isg::run::metricsToJson(metrics);
  const nlohmann::json again =
      isg::run::metricsToJson(isg::run::metricsFromJson(written, "fuzz/written.json"));
  if (written != again) std::abort();
  return 0;
}
