#pragma once

#include "run/run_record.hpp"
#include "sensors/messages.hpp"

namespace isg::run {

// Offers a scan the localizer read to the run's map sample (RunRecord::map_samples): kept, thinned
// to every kMapSampleStride-th point, when it comes map_sample_seconds or more after the last
// one kept. When kMaxMapSamples are kept, every other one (the second, fourth, …) is dropped and
// the spacing doubles: the samples stay evenly spread over the whole run, their number bounded,
// and a run shorter than kMaxMapSamples seconds keeps one a second as before.
void offerMapSample(RunRecord& record, const sensors::Scan& scan);

}  // namespace isg::run
