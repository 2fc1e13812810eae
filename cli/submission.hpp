#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bim/scenario.hpp"
#include "run/run_record.hpp"

namespace isg::cli {

// isg run --submission DIR: the run's estimate as the floor-plan benchmark takes a submission
// (docs/evaluation.md, "Submissions"): DIR/SEQUENCE.txt, TUM, one pose for each stamp of the
// recording — a replayed walk's own stamps in its own clock (SEQUENCE its file's name without the
// extension, as the benchmark names its runs), else the ground truth's (SEQUENCE the world's
// name) — the estimate resampled there (eval::estimateAtStamps).
struct SubmissionTarget {
  std::filesystem::path file;
  std::string sequence;
};

// Where it goes, checked before the run: DIR may exist or not; a file of that name is replaced
// only when isg wrote it and `force` is given. An InputError names what is wrong.
SubmissionTarget planSubmission(const std::string& dir, const bim::Scenario& scenario,
                                const std::string& input, bool force,
                                const std::vector<std::string>& inputs);

// Writes it (atomically, parent folders made); returns the poses written and the stamps asked.
std::pair<std::size_t, std::size_t> writeSubmission(const SubmissionTarget& target,
                                                    const bim::Scenario& scenario,
                                                    const run::RunRecord& record);

}  // namespace isg::cli
