#include "worlds/columns_as_built.hpp"

#include <cmath>
#include <random>

#include "worlds/millimetres.hpp"

namespace isg::worlds {

void columnsAsBuilt(const GeneratorSpec& spec, const std::vector<std::size_t>& candidates,
                    const bim::Level& level, bim::AsBuilt& as_built) {
  if (!(spec.missing_columns > 0.0 || spec.moved_columns > 0.0)) return;
  std::mt19937_64 column_rng(spec.seed * 0xA24BAED4963EE407ULL + 29);
  std::uniform_real_distribution<double> column_unit(0.0, 1.0);
  for (std::size_t k : candidates) {
    const double draw = column_unit(column_rng);
    const double distance = mm(0.1 + 0.15 * column_unit(column_rng));
    const double direction = 2.0 * 3.14159265358979 * column_unit(column_rng);
    const std::string& id = level.columns[k].id;
    if (draw < spec.missing_columns) {
      as_built.missing_columns.push_back(id);
    } else if (draw < spec.missing_columns + spec.moved_columns) {
      as_built.moved_columns.push_back(
          {id, {mm(distance * std::cos(direction)), mm(distance * std::sin(direction))}});
    }
  }
}

}  // namespace isg::worlds
