#include "worlds/parking_generator.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "bim/plan_json.hpp"
#include "worlds/columns_as_built.hpp"
#include "worlds/grid_floor_drawing.hpp"
#include "worlds/millimetres.hpp"
#include "worlds/segment_distance.hpp"

namespace isg::worlds {

namespace {

using json = nlohmann::json;

// Between any two things on the floor, so that the robot (0.35 m clearance) passes and the tour
// reaches every part of the slab; the same as a site's.
constexpr double kParkingPassage = 1.2;  // m
constexpr double kPerimeterThickness = 0.3;
constexpr double kParkingCoreThickness = 0.2;
constexpr double kRampThickness = 0.2;

// A wall's or a column's axis and thickness, or an edge of a parked thing (thickness 0).
using Solid = GridFloorDrawing::Solid;

// Free space between two solids' faces; 0 or less where they cross or touch.
double clearanceBetween(const Solid& s, const Solid& t) {
  if (crosses(s.a, s.b, t.a, t.b)) return 0.0;
  return worlds::segmentDistance(s.a, s.b, t.a, t.b) - 0.5 * (s.thickness + t.thickness);
}

// A core: a lobby opening onto the floor through a doorway in its outer wall, and behind a cross
// wall a stair (a door from the lobby) or a lift shaft (closed). Unmirrored slab coordinates.
struct Core {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Zero();
  bool stair = true;
  double lobby_depth = 0.0;  // from lo.y
  Eigen::Vector2d hi() const { return lo + size; }
};

// The car park's plan as drawn, step by step from one stream: slab → ramp → cores → columns →
// perimeter → ramp walls → cores' walls. The order of the steps is the order of the draws.
class ParkingDrawing : public GridFloorDrawing {
 public:
  explicit ParkingDrawing(const GeneratorSpec& spec)
      : GridFloorDrawing(spec.seed * 0x9E3779B97F4A7C15ULL + 17, spec.height) {}

  void drawSlab() {
    bay_x = mm(uniform(7.5, 8.5));
    bay_y = mm(uniform(7.5, 8.5));
    bays_x = count(6, 9);
    bays_y = count(4, 6);
    width = bays_x * bay_x;
    depth = bays_y * bay_y;
    mirror_x_ = unit() < 0.5;
    mirror_y_ = unit() < 0.5;
    round_columns = unit() < 0.5;
    column_ = mm(uniform(0.5, 0.7));
    column_half_width = 0.5 * column_;
    ramp_edge_y = place({0.0, 0.0}).y();
  }

  // The ramp's lane: centred in a bay of the south edge (before mirroring), 3.5–4 m wide.
  void placeRamp() {
    const int bay = count(1, bays_x - 2);
    ramp_lane_ = mm(uniform(3.5, 4.0));
    ramp_x0_ = mm(bay * bay_x + 0.5 * (bay_x - ramp_lane_));
    ramp_length_ = mm(bay_y * uniform(1.3, 1.8));
  }

  // A stair core and a lift core, clear of the perimeter, the ramp and each other by two
  // passages; a core that finds no place in 200 draws is left out (a small slab).
  void placeCores() {
    for (const bool stair : {true, false}) {
      Core core;
      core.stair = stair;
      core.size = stair ? Eigen::Vector2d(mm(uniform(3.2, 3.8)), mm(uniform(6.0, 7.0)))
                        : Eigen::Vector2d(mm(uniform(2.6, 3.0)), mm(uniform(5.0, 5.6)));
      core.lobby_depth = mm(core.size.y() * uniform(0.4, 0.5));
      for (int attempt = 0; attempt < 200; ++attempt) {
        core.lo = {mm(uniform(3.0, width - 3.0 - core.size.x())),
                   mm(uniform(3.0, depth - 3.0 - core.size.y()))};
        if (coreIsClear(core)) {
          cores.push_back(core);
          break;
        }
      }
    }
  }

  // Square columns on the perimeter at every bay; inside, on the grid, square or round as the
  // floor's are, none by a core or a ramp wall.
  void drawColumns() {
    for (int i = 0; i <= bays_x; ++i) {
      for (int j = 0; j <= bays_y; ++j) {
        const bool edge = i == 0 || j == 0 || i == bays_x || j == bays_y;
        const Eigen::Vector2d c(i * bay_x, j * bay_y);
        if (!edge && (nearACore(c, kParkingPassage + 0.5 * column_ + kParkingCoreThickness) ||
                      nearTheRamp(c, kParkingPassage + 0.5 * column_ + kRampThickness))) {
          continue;
        }
        addColumn(c, !edge);
      }
    }
  }

  // The retaining walls from column face to column face round the slab; the ramp's bay in two
  // pieces either side of its lane, which is the way out.
  void drawPerimeter() {
    const auto piece = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
      if ((b - a).norm() < 0.5) return;
      const std::string id = "E" + std::to_string(perimeter_walls.size() + 1);
      addWall(id, a, b, kPerimeterThickness, "perimeter");
      perimeter_walls.push_back(id);
    };
    const double half = 0.5 * column_;
    for (int i = 0; i < bays_x; ++i) {
      for (const double y : {0.0, depth}) {
        const Eigen::Vector2d a(i * bay_x + half, y), b((i + 1) * bay_x - half, y);
        if (y == 0.0 && a.x() < ramp_x0_ && b.x() > ramp_x0_) {
          piece(a, {ramp_x0_, y});
          piece({ramp_x0_ + ramp_lane_, y}, b);
        } else {
          piece(a, b);
        }
      }
    }
    for (int j = 0; j < bays_y; ++j) {
      for (const double x : {0.0, width}) piece({x, j * bay_y + half}, {x, (j + 1) * bay_y - half});
    }
  }

  void drawRamp() {
    for (const double x : {ramp_x0_, ramp_x0_ + ramp_lane_}) {
      addWall("RW" + std::to_string(++ramp_walls_), {x, 0.0}, {x, ramp_length_}, kRampThickness,
              "ramp");
    }
  }

  // Each core's outline, its doorway onto the floor in the lobby's outer wall, and the cross
  // wall (with a door into a stair; closed before a shaft).
  void drawCores() {
    for (const Core& core : cores) {
      const Eigen::Vector2d lo = core.lo, hi = core.hi();
      const double cross_y = lo.y() + core.lobby_depth;
      coreWall(lo, {lo.x(), hi.y()});
      coreWall({hi.x(), lo.y()}, hi);
      coreWall({lo.x(), hi.y()}, hi);
      wallWithDoorway(lo, {hi.x(), lo.y()}, mm(uniform(1.0, 1.4)));
      if (core.stair) {
        wallWithDoorway({lo.x(), cross_y}, {hi.x(), cross_y}, mm(uniform(0.9, 1.1)));
      } else {
        coreWall({lo.x(), cross_y}, {hi.x(), cross_y});
      }
    }
  }

  Eigen::Vector2d place(Eigen::Vector2d p) const {
    if (mirror_x_) p.x() = width - p.x();
    if (mirror_y_) p.y() = depth - p.y();
    return p;
  }

  double bay_x = 0, bay_y = 0, width = 0, depth = 0;
  int bays_x = 0, bays_y = 0;
  double ramp_edge_y = 0;  // the edge the ramp leaves from, as placed (mirrored)
  double column_half_width = 0;
  bool round_columns = false;
  std::vector<Core> cores;
  std::vector<std::string> perimeter_walls;
  std::vector<std::size_t> inner_columns;

 private:
  bool nearACore(const Eigen::Vector2d& p, double margin) const {
    return std::any_of(cores.begin(), cores.end(), [&](const Core& c) {
      return p.x() > c.lo.x() - margin && p.x() < c.hi().x() + margin &&
             p.y() > c.lo.y() - margin && p.y() < c.hi().y() + margin;
    });
  }
  bool nearTheRamp(const Eigen::Vector2d& p, double margin) const {
    return p.y() < ramp_length_ + margin && p.x() > ramp_x0_ - margin &&
           p.x() < ramp_x0_ + ramp_lane_ + margin;
  }
  // Two passages from the perimeter, the ramp and the other core, so that the columns between
  // can still stand or be left out without shutting a way.
  bool coreIsClear(const Core& core) const {
    const double margin = 2.0 * kParkingPassage;
    if (core.lo.x() < margin || core.lo.y() < margin || core.hi().x() > width - margin ||
        core.hi().y() > depth - margin) {
      return false;
    }
    for (const Eigen::Vector2d& corner :
         {core.lo, core.hi(), Eigen::Vector2d(core.lo.x(), core.hi().y()),
          Eigen::Vector2d(core.hi().x(), core.lo.y())}) {
      if (nearTheRamp(corner, margin)) return false;
    }
    const bool over_ramp = core.lo.x() < ramp_x0_ + ramp_lane_ + margin &&
                           core.hi().x() > ramp_x0_ - margin && core.lo.y() < ramp_length_ + margin;
    if (over_ramp) return false;
    return !std::any_of(cores.begin(), cores.end(), [&](const Core& c) {
      return core.lo.x() < c.hi().x() + margin && core.hi().x() > c.lo.x() - margin &&
             core.lo.y() < c.hi().y() + margin && core.hi().y() > c.lo.y() - margin;
    });
  }

  void addWall(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
               double thickness, const std::string& name) {
    addPlacedWall(id, place(a), place(b), thickness, name);
  }
  void coreWall(Eigen::Vector2d a, Eigen::Vector2d b) {
    addWall("K" + std::to_string(++core_walls_), a, b, kParkingCoreThickness, "core");
  }
  // Along x from a to b, with a doorway of `door` metres somewhere clear of both ends.
  void wallWithDoorway(Eigen::Vector2d a, Eigen::Vector2d b, double door) {
    const double room = b.x() - a.x();
    const double mid = mm(a.x() + std::clamp(0.5 * room + uniform(-0.4, 0.4), 0.3 + 0.5 * door,
                                             room - 0.3 - 0.5 * door));
    coreWall(a, {mid - 0.5 * door, a.y()});
    coreWall({mid + 0.5 * door, a.y()}, b);
  }

  void addColumn(const Eigen::Vector2d& c, bool inner) {
    const std::size_t index = addPlacedColumn(place(c), column_, inner && round_columns);
    if (inner) inner_columns.push_back(index);
  }

  bool mirror_x_ = false, mirror_y_ = false;
  double column_ = 0.0;
  double ramp_lane_ = 0.0, ramp_x0_ = 0.0, ramp_length_ = 0.0;
  int core_walls_ = 0, ramp_walls_ = 0;
};

// A box's four edges on the floor.
std::vector<Solid> footprintEdges(const Eigen::Vector2d& centre, const Eigen::Vector2d& size,
                                  double yaw) {
  const Eigen::Vector2d u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
  const Eigen::Vector2d hu = 0.5 * size.x() * u, hv = 0.5 * size.y() * v;
  const Eigen::Vector2d p[4] = {centre - hu - hv, centre + hu - hv, centre + hu + hv,
                                centre - hu + hv};
  std::vector<Solid> edges;
  for (int k = 0; k < 4; ++k) edges.push_back({p[k], p[(k + 1) % 4], 0.0});
  return edges;
}

// Vehicles parked between the columns (along or across the grid, a little askew) and pallets of
// material, each a passage clear of every wall, column and other thing, inside the perimeter.
std::vector<bim::Clutter> parkedThings(const ParkingDrawing& park, std::mt19937_64& built_rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int vehicles = 4 + int(built_rng() % 9), pallets = 2 + int(built_rng() % 4);
  std::vector<Solid> taken = park.solids;
  std::vector<bim::Clutter> clutter;
  int placed_vehicles = 0, placed_pallets = 0;
  for (int attempt = 0; attempt < 2000 && placed_vehicles + placed_pallets < vehicles + pallets;
       ++attempt) {
    const bool vehicle = placed_vehicles < vehicles;
    const Eigen::Vector3d size =
        vehicle ? Eigen::Vector3d(mm(4.2 + 0.7 * unit(built_rng)), mm(1.75 + 0.2 * unit(built_rng)),
                                  mm(1.4 + 0.3 * unit(built_rng)))
                : Eigen::Vector3d(1.2, 1.0, mm(0.4 + unit(built_rng)));
    const double yaw = mm((built_rng() % 2 == 0 ? 0.0 : 1.5707963) + 0.1 * (unit(built_rng) - 0.5));
    const Eigen::Vector2d centre(mm(park.width * unit(built_rng)),
                                 mm(park.depth * unit(built_rng)));
    const double reach = 0.5 * size.head<2>().norm() + kParkingPassage + 0.5;
    if (centre.x() < reach || centre.y() < reach || centre.x() > park.width - reach ||
        centre.y() > park.depth - reach) {
      continue;
    }
    const std::vector<Solid> edges = footprintEdges(centre, size.head<2>(), yaw);
    bool clear = true;
    for (const Solid& s : taken) {
      const Eigen::Vector2d mid = 0.5 * (s.a + s.b);
      if ((mid - centre).norm() < 0.5 * size.head<2>().norm()) clear = false;  // inside it
      for (const Solid& e : edges) clear = clear && clearanceBetween(e, s) >= kParkingPassage;
      if (!clear) break;
    }
    if (!clear) continue;
    taken.insert(taken.end(), edges.begin(), edges.end());
    bim::Clutter box;
    box.center = {centre.x(), centre.y(), mm(0.5 * size.z())};
    box.size = size;
    box.yaw = yaw;
    clutter.push_back(box);
    (vehicle ? placed_vehicles : placed_pallets) += 1;
  }
  return clutter;
}

// A part of the site the plan does not show, on 7 car parks in 10: beyond a perimeter bay left
// open (not on the ramp's edge), a bay built outside the slab, 0.6–1 bay deep, walled on three
// sides (as_built.extra_walls, 0.2 m), which the tour walks into (sim/route_planner.cpp,
// touredOutline): the walk leaves the drawn outline there for a while.
constexpr double kAnnexShare = 0.7;

void addAnnex(const ParkingDrawing& park, std::mt19937_64& built_rng, bim::AsBuilt& as_built) {
  std::vector<const bim::Wall*> bays;
  for (const auto& wall : park.level.walls) {
    const bool on_ramp_edge = std::abs(wall.start.y() - park.ramp_edge_y) < 1e-6 &&
                              std::abs(wall.end.y() - park.ramp_edge_y) < 1e-6;
    const double bay = std::abs(wall.end.x() - wall.start.x()) > 1e-6 ? park.bay_x : park.bay_y;
    if (wall.name == "perimeter" && !on_ramp_edge && (wall.end - wall.start).norm() > bay - 1.0) {
      bays.push_back(&wall);
    }
  }
  if (bays.empty()) return;
  const bim::Wall& gap = *bays[std::size_t(built_rng() % bays.size())];
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d along = (gap.end - gap.start).normalized();
  Eigen::Vector2d out(along.y(), -along.x());
  const Eigen::Vector2d middle(0.5 * park.width, 0.5 * park.depth);
  if (out.dot(0.5 * (gap.start + gap.end) - middle) < 0) out = -out;
  const double bay = std::abs(along.x()) > 0.5 ? park.bay_x : park.bay_y;
  const double deep = mm(bay * (0.6 + 0.4 * unit(built_rng)));
  // From the outer faces of the bay's two columns (the gap's ends are their inner faces).
  const double half = park.column_half_width;
  const Eigen::Vector2d a = gap.start - half * along + (half + 0.1) * out;
  const Eigen::Vector2d b = gap.end + half * along + (half + 0.1) * out;
  const auto wall = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    bim::ExtraWall extra;
    extra.start = {mm(from.x()), mm(from.y())};
    extra.end = {mm(to.x()), mm(to.y())};
    extra.thickness = 0.2;
    as_built.extra_walls.push_back(extra);
  };
  wall(a, a + deep * out);
  wall(a + deep * out, b + deep * out);
  wall(b + deep * out, b);
  if (std::find(as_built.missing_walls.begin(), as_built.missing_walls.end(), gap.id) ==
      as_built.missing_walls.end()) {
    as_built.missing_walls.push_back(gap.id);
  }
}

// The car park as built against its plan: perimeter walls not built yet, the parked things, and
// on request columns missing or moved.
bim::AsBuilt parkingAsBuilt(const GeneratorSpec& spec, const ParkingDrawing& park) {
  std::mt19937_64 built_rng(spec.seed * 0xD1B54A32D192ED03ULL + 19);
  bim::AsBuilt as_built;
  std::vector<std::string> open = park.perimeter_walls;
  std::shuffle(open.begin(), open.end(), built_rng);
  const int unbuilt = std::min<int>(int(open.size()) / 4, 1 + int(built_rng() % 3));
  for (int k = 0; k < unbuilt; ++k) as_built.missing_walls.push_back(open[std::size_t(k)]);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (unit(built_rng) < kAnnexShare) addAnnex(park, built_rng, as_built);
  as_built.clutter = parkedThings(park, built_rng);
  columnsAsBuilt(spec, park.inner_columns, park.level, as_built);
  return as_built;
}

}  // namespace

GeneratedBuilding generateParking(const GeneratorSpec& spec) {
  ParkingDrawing park(spec);
  park.drawSlab();
  park.placeRamp();
  park.placeCores();
  park.drawColumns();
  park.drawPerimeter();
  park.drawRamp();
  park.drawCores();

  GeneratedBuilding out;
  out.name = spec.family + "-" + std::to_string(spec.seed);
  out.as_built = parkingAsBuilt(spec, park);
  char title[200];
  std::snprintf(title, sizeof title,
                "generated car park: %.0f × %.0f m, %d × %d bays, %zu %s columns, %zu perimeter "
                "walls, a ramp, %zu cores, seed %llu",
                park.width, park.depth, park.bays_x, park.bays_y, park.level.columns.size(),
                park.round_columns ? "square and round" : "square", park.perimeter_walls.size(),
                park.cores.size(), (unsigned long long)spec.seed);
  bim::Plan plan;
  plan.name = title;
  plan.levels.push_back(park.level);
  out.plan = json::parse(
      bim::planToJson(plan, {.every_wall_height = false, .inferred_door_rooms = false}).dump());
  out.scenario = {{"format", "isg.scenario"},
                  {"version", 1},
                  {"plan", out.name + ".json"},
                  {"seed", spec.seed},
                  {"robot", {{"level", "L0"}, {"route", "tour"}}},
                  {"as_built", generatedAsBuiltJson(out.as_built)}};
  return out;
}

}  // namespace isg::worlds
