#include "bim/synthetic_plan.hpp"

#include <random>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "bim/plan_json.hpp"

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
  const std::vector<double> xs = lines(spec.cols, spec.cell_width, spec.size_seed);
  // Rows draw from another stream than columns.
  const std::vector<double> ys =
      lines(spec.rows, spec.cell_depth, spec.size_seed == 0 ? 0 : spec.size_seed ^ 0x9e3779b9ULL);
  const double half = 0.5 * spec.wall_thickness;
  auto room_id = [&](int r, int c) { return "R" + std::to_string(r * spec.cols + c + 1); };

  Level level;
  level.id = "L0";
  level.height = spec.height;
  auto addWall = [&](const std::string& id, Eigen::Vector2d start, Eigen::Vector2d end) {
    Wall wall;
    wall.id = id;
    wall.start = start;
    wall.end = end;
    wall.thickness = spec.wall_thickness;
    wall.height = spec.height;
    level.walls.push_back(wall);
  };
  // A door of 0.9 × 2.1 m; its rooms given only when the spec says so (else the parser infers
  // them from the outlines).
  auto addDoor = [&](const std::string& id, const std::string& wall, double offset,
                     std::array<std::string, 2> rooms) {
    Door door;
    door.id = id;
    door.wall = wall;
    door.offset = offset;
    door.width = 0.9;
    door.height = 2.1;
    door.rooms = std::move(rooms);
    door.rooms_inferred = !spec.give_door_rooms;
    level.doors.push_back(door);
  };
  for (int r = 0; r <= spec.rows; ++r) {
    const std::string id = "H" + std::to_string(r);
    addWall(id, {xs.front(), ys[r]}, {xs.back(), ys[r]});
    for (int c = 0; c < spec.cols; ++c) {
      const bool outside_door = (r == 0 && c == 0);
      if ((r == 0 || r == spec.rows) && !outside_door) continue;
      // The left of a wall running +x is +y: the room above comes first.
      addDoor("D" + id + "_" + std::to_string(c), id, 0.5 * (xs[c] + xs[c + 1]),
              {r < spec.rows ? room_id(r, c) : kOutside, r > 0 ? room_id(r - 1, c) : kOutside});
    }
  }
  for (int c = 0; c <= spec.cols; ++c) {
    const std::string id = "V" + std::to_string(c);
    addWall(id, {xs[c], ys.front()}, {xs[c], ys.back()});
    if (c == 0 || c == spec.cols) continue;
    for (int r = 0; r < spec.rows; ++r) {
      // The left of a wall running +y is -x.
      addDoor("D" + id + "_" + std::to_string(r), id, 0.5 * (ys[r] + ys[r + 1]) - ys.front() + 0.4,
              {room_id(r, c - 1), room_id(r, c)});
    }
  }
  for (int r = 0; r < spec.rows; ++r) {
    for (int c = 0; c < spec.cols; ++c) {
      const double x0 = xs[c] + half, x1 = xs[c + 1] - half;
      const double y0 = ys[r] + half, y1 = ys[r + 1] - half;
      Room room;
      room.id = room_id(r, c);
      room.name = "Room " + std::to_string(r) + "," + std::to_string(c);
      room.outline = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
      level.rooms.push_back(room);
    }
  }
  Plan plan;
  plan.name = "grid " + std::to_string(spec.rows) + "x" + std::to_string(spec.cols);
  plan.levels.push_back(level);
  return nlohmann::json::parse(
      planToJson(plan, {.every_wall_height = false, .inferred_door_rooms = false}).dump());
}

}  // namespace isg::bim
