#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "bim/plan.hpp"

namespace isg::worlds {

// What the column-grid families (site, parking) draw with: the floor's one random stream (the
// order of the draws is the order of the steps that make the floor), its level, and every wall
// and column as placed, for spacing what is drawn after them. Coordinates come in placed (each
// family turns its floor to a corner of its own by mirroring) and go out on the millimetre grid.
class GridFloorDrawing {
 public:
  // A wall's axis and thickness, or a column as a segment across it with its width.
  struct Solid {
    Eigen::Vector2d a, b;
    double thickness;
  };

  bim::Level level;
  std::vector<Solid> solids;

 protected:
  GridFloorDrawing(std::uint64_t stream_seed, double height);

  double unit() { return unit_(rng_); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit_(rng_); }
  int count(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  // A wall of the level from a to b (both placed).
  void addPlacedWall(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     double thickness, const std::string& name);
  // A column "C<n>" of `width` across, square or round, centred at `centre` (placed), as tall as
  // the level; its index in level.columns.
  std::size_t addPlacedColumn(const Eigen::Vector2d& centre, double width, bool round);

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

}  // namespace isg::worlds
