#pragma once

#include <string>

#include "bim/scenario.hpp"
#include "sim/simulation.hpp"

namespace isg::cli {

// What `isg simulate` and `isg run` say about the route before they start: a warning for each
// room a tour cannot reach and for a --duration longer than the route (the run ends with the
// route); an InputError naming the scenario's route when the robot would record no scan at all
// (a one-room plan's tour, every door closed), so that no empty run ever exits 0.
// `duration` is --duration, negative for the whole route. Returns the seconds that will be run.
double checkRoute(const std::string& command, const bim::Scenario& scenario,
                  const sim::Simulation& simulation, double duration);

}  // namespace isg::cli
