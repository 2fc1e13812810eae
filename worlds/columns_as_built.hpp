#pragma once

#include <cstddef>
#include <vector>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"
#include "worlds/plan_generator.hpp"

namespace isg::worlds {

// The columns of a column-grid floor (site, parking) not built yet or built off their place, on
// request (--missing-columns, --moved-columns): from a stream of their own, so that the rest of
// the floor is the same bytes either way. Only `candidates` (indices into level.columns: the
// columns standing free inside the façade) are drawn. A column moves 0.1–0.25 m, clear of the
// 6 cm a report calls moved, never onto a wall or another column (the grids are 6 m and wider).
void columnsAsBuilt(const GeneratorSpec& spec, const std::vector<std::size_t>& candidates,
                    const bim::Level& level, bim::AsBuilt& as_built);

}  // namespace isg::worlds
