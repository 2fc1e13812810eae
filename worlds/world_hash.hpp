#pragma once

#include <string>

#include "bim/scenario.hpp"

namespace isg::worlds {

// The content hash of the world a scenario was loaded from (common::contentHash): its file's bytes
// (a built-in's text), those of the plan file it names, and a replayed walk's poses. Two files of
// one name with different buildings differ; the same building under two paths does not. Recorded in
// metrics.json and sweep.json (docs/sweeps.md) so that results of different worlds are never mixed.
std::string worldHash(const bim::Scenario& scenario);

}  // namespace isg::worlds
