#include "bim/synthetic_plan.hpp"

#include <random>
#include <string>
#include <vector>

namespace isg::bim {

namespace {

// Deterministic size variation: ±20 % in a fixed pattern, no random generator needed.
double varied(double mean, int index) {
  static constexpr double kPattern[] = {0.0, 0.15, -0.1, 0.2, -0.2, 0.05, -0.05, 0.1};
  return mean * (1.0 + kPattern[index % 8]);
}

std::vector<double> lines(int count, double mean, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> factor(0.8, 1.2);
  std::vector<double> out{0.0};
  for (int i = 0; i < count; ++i) {
    out.push_back(out.back() + (seed == 0 ? varied(mean, i) : mean * factor(rng)));
  }
  return out;
}

}  // namespace

nlohmann::json makeGridPlan(const GridPlanSpec& spec) {
  using nlohmann::json;
  const std::vector<double> xs = lines(spec.cols, spec.cell_width, spec.size_seed);
  // Rows draw from another stream than columns.
  const std::vector<double> ys =
      lines(spec.rows, spec.cell_depth, spec.size_seed == 0 ? 0 : spec.size_seed ^ 0x9e3779b9ULL);
  const double half = 0.5 * spec.wall_thickness;
  auto room_id = [&](int r, int c) { return "R" + std::to_string(r * spec.cols + c + 1); };

  json walls = json::array();
  json doors = json::array();
  json rooms = json::array();
  for (int r = 0; r <= spec.rows; ++r) {
    const std::string id = "H" + std::to_string(r);
    walls.push_back({{"id", id},
                     {"start", {xs.front(), ys[r]}},
                     {"end", {xs.back(), ys[r]}},
                     {"thickness", spec.wall_thickness}});
    for (int c = 0; c < spec.cols; ++c) {
      const bool outside_door = (r == 0 && c == 0);
      if ((r == 0 || r == spec.rows) && !outside_door) continue;
      json door = {{"id", "D" + id + "_" + std::to_string(c)},
                   {"wall", id},
                   {"offset", 0.5 * (xs[c] + xs[c + 1])},
                   {"width", 0.9},
                   {"height", 2.1}};
      if (spec.give_door_rooms) {
        // The left of a wall running +x is +y: the room above comes first.
        door["rooms"] = {r < spec.rows ? room_id(r, c) : "outside",
                         r > 0 ? room_id(r - 1, c) : "outside"};
      }
      doors.push_back(door);
    }
  }
  for (int c = 0; c <= spec.cols; ++c) {
    const std::string id = "V" + std::to_string(c);
    walls.push_back({{"id", id},
                     {"start", {xs[c], ys.front()}},
                     {"end", {xs[c], ys.back()}},
                     {"thickness", spec.wall_thickness}});
    if (c == 0 || c == spec.cols) continue;
    for (int r = 0; r < spec.rows; ++r) {
      json door = {{"id", "D" + id + "_" + std::to_string(r)},
                   {"wall", id},
                   {"offset", 0.5 * (ys[r] + ys[r + 1]) - ys.front() + 0.4},
                   {"width", 0.9},
                   {"height", 2.1}};
      if (spec.give_door_rooms) {
        // The left of a wall running +y is -x.
        door["rooms"] = {room_id(r, c - 1), room_id(r, c)};
      }
      doors.push_back(door);
    }
  }
  for (int r = 0; r < spec.rows; ++r) {
    for (int c = 0; c < spec.cols; ++c) {
      const double x0 = xs[c] + half, x1 = xs[c + 1] - half;
      const double y0 = ys[r] + half, y1 = ys[r + 1] - half;
      rooms.push_back({{"id", room_id(r, c)},
                       {"name", "Room " + std::to_string(r) + "," + std::to_string(c)},
                       {"outline", {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
    }
  }
  return {{"format", "isg.plan"},
          {"version", 1},
          {"name", "grid " + std::to_string(spec.rows) + "x" + std::to_string(spec.cols)},
          {"levels",
           {{{"id", "L0"},
             {"elevation", 0.0},
             {"height", spec.height},
             {"walls", walls},
             {"doors", doors},
             {"rooms", rooms}}}}};
}

}  // namespace isg::bim
