#pragma once

#include <string>
#include <vector>

#include "sweep/suite.hpp"

namespace isg::sweep {

// The sweep folder's policy (docs/sweeps.md): what `isg sweep SUITE -o DIR` may write into and
// when it may start again in a folder it wrote before.

// The output rule (not the working directory or what holds it, not the suite or its world files,
// an existing folder only if it is a sweep's or empty), then the folder made. Bad input names
// `output`.
void startSweepFolder(const std::string& output, const std::string& suite_file, const Suite& suite);

// A folder started before must hold the same cells (else bad input naming its sweep.json), of
// the same worlds: a changed world is bad input naming the suite, unless `rerun_changed`, when its
// finished and damaged cells, with their failure records, are moved aside to run again.
void checkAgainstEarlierStart(const std::string& output, const std::string& suite_file,
                              const Suite& suite, const std::vector<SweepCell>& cells,
                              bool rerun_changed);

}  // namespace isg::sweep
