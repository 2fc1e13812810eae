#include "run/map_samples.hpp"

#include <utility>

namespace isg::run {

void offerMapSample(RunRecord& record, const sensors::Scan& scan) {
  auto& samples = record.map_samples;
  if (!samples.empty() && scan.stamp < samples.back().stamp + record.map_sample_seconds - 1e-9) {
    return;
  }
  if (samples.size() >= kMaxMapSamples) {
    // The first stays where it is (moving it onto itself would empty it).
    std::size_t kept = 1;
    for (std::size_t i = 2; i < samples.size(); i += 2) samples[kept++] = std::move(samples[i]);
    samples.resize(kept);
    samples.shrink_to_fit();
    record.map_sample_seconds *= 2.0;
    // The scan may now come too soon after the last one kept.
    if (scan.stamp < samples.back().stamp + record.map_sample_seconds - 1e-9) return;
  }
  MapScanSample sample{scan.stamp, {}};
  sample.points.reserve(scan.points.size() / kMapSampleStride + 1);
  for (std::size_t i = 0; i < scan.points.size(); i += kMapSampleStride) {
    const auto& p = scan.points[i];
    sample.points.push_back({p.x, p.y, p.z, p.time});
  }
  samples.push_back(std::move(sample));
}

}  // namespace isg::run
