#include "worlds/site_generator.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
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

// How far apart things stand on the floor, so that the robot (0.35 m clearance) passes between
// any two of them and the tour reaches every part of the slab.
constexpr double kPassage = 1.2;  // m
constexpr double kFacadeThickness = 0.25;
constexpr double kCoreThickness = 0.2;
constexpr double kPartitionThickness = 0.1;

using Segment = GridFloorDrawing::Solid;

// Between two walls' axes: 0 where they cross or touch.
double segmentDistance(const Segment& s, const Segment& t) {
  return crosses(s.a, s.b, t.a, t.b) ? 0.0 : worlds::segmentDistance(s.a, s.b, t.a, t.b);
}

// The slab's outline, counter-clockwise: a rectangle W × D, or one with its corner `cut` cut from
// (W − cx, 0) to (W, cy) (the corner turned to where the seed says afterwards, by mirroring).
struct Slab {
  double width = 0, depth = 0;
  double bay_x = 0, bay_y = 0;
  bool cut = false;
  double cut_x = 0, cut_y = 0;
  bool mirror_x = false, mirror_y = false;

  Eigen::Vector2d place(Eigen::Vector2d p) const {
    if (mirror_x) p.x() = width - p.x();
    if (mirror_y) p.y() = depth - p.y();
    return p;
  }
  // Inside the unmirrored outline by at least `margin`.
  bool inside(const Eigen::Vector2d& p, double margin) const {
    if (p.x() < margin || p.y() < margin || p.x() > width - margin || p.y() > depth - margin)
      return false;
    if (!cut) return true;
    // The cut's line from (W − cx, 0) to (W, cy); inside is to its left.
    const Eigen::Vector2d a(width - cut_x, 0.0), b(width, cut_y);
    const Eigen::Vector2d d = (b - a).normalized();
    return d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x()) >= margin;
  }
  std::vector<Eigen::Vector2d> corners() const {
    if (!cut) return {{0, 0}, {width, 0}, {width, depth}, {0, depth}};
    return {{0, 0}, {width - cut_x, 0}, {width, cut_y}, {width, depth}, {0, depth}};
  }
};

// The site's plan as it is drawn, step by step from one random stream: slab → columns →
// façade → core → partitions. The order of the steps is the order of the draws: a site is the
// same bytes for a seed as long as it is kept.
class SiteDrawing : public GridFloorDrawing {
 public:
  explicit SiteDrawing(const GeneratorSpec& spec)
      : GridFloorDrawing(spec.seed * 0x9E3779B97F4A7C15ULL + 3, spec.height) {}

  void drawSlab() {
    slab.bay_x = mm(uniform(6.0, 8.0));
    slab.bay_y = mm(uniform(6.0, 8.0));
    bays_x_ = count(4, 6), bays_y_ = count(3, 4);
    slab.width = bays_x_ * slab.bay_x;
    slab.depth = bays_y_ * slab.bay_y;
    slab.cut = unit() < 0.7;
    if (slab.cut) {
      slab.cut_x = mm(slab.bay_x * uniform(1.0, 2.0));
      slab.cut_y = mm(slab.bay_y * uniform(0.8, 1.6));
    }
    slab.mirror_x = unit() < 0.5;
    slab.mirror_y = unit() < 0.5;
    column_ = mm(uniform(0.4, 0.6));
  }

  // The core: an off-centre block of small rooms, clear of the cut.
  void placeCore() {
    core_w_ = mm(uniform(8.0, 12.0)), core_d_ = mm(uniform(5.0, 7.0));
    for (int attempt = 0;; ++attempt) {
      core_lo_ = {mm(uniform(slab.bay_x, slab.width - slab.bay_x - core_w_)),
                  mm(uniform(0.7 * slab.bay_y, slab.depth - 0.7 * slab.bay_y - core_d_))};
      const bool clear = slab.inside(core_lo_, 3.0) &&
                         slab.inside(core_lo_ + Eigen::Vector2d(core_w_, 0), 3.0) &&
                         slab.inside(core_lo_ + Eigen::Vector2d(core_w_, core_d_), 3.0) &&
                         slab.inside(core_lo_ + Eigen::Vector2d(0, core_d_), 3.0);
      if (clear || attempt > 100) break;
    }
    core_hi_ = core_lo_ + Eigen::Vector2d(core_w_, core_d_);
  }

  // Columns: on the grid, on the façade (its straight edges and its cut) and inside, none in or
  // by the core.
  void drawColumns() {
    const std::vector<Eigen::Vector2d> outline = slab.corners();
    for (std::size_t e = 0; e < outline.size(); ++e) {
      const Eigen::Vector2d a = outline[e], b = outline[(e + 1) % outline.size()];
      const double length = (b - a).norm();
      const double bay = std::abs((b - a).x()) > std::abs((b - a).y()) ? slab.bay_x : slab.bay_y;
      const int steps = std::max(1, int(std::round(length / bay)));
      for (int k = 0; k < steps; ++k) facade_columns_.push_back(a + (b - a) * (double(k) / steps));
    }
    for (const auto& c : facade_columns_) addColumn(c, false);
    for (int i = 1; i < bays_x_; ++i) {
      for (int j = 1; j < bays_y_; ++j) {
        const Eigen::Vector2d c(i * slab.bay_x, j * slab.bay_y);
        if (!slab.inside(c, 1.5) || nearCore(c, kPassage + 0.5 * column_)) continue;
        addColumn(c, true);
      }
    }
  }

  // The façade's bays: a wall with a window from column to column, or still open; at least half
  // of them closed, so that the floor has walls to be known by.
  void drawFacade() {
    for (std::size_t k = 0; k < facade_columns_.size(); ++k) {
      const Eigen::Vector2d a = facade_columns_[k],
                            b = facade_columns_[(k + 1) % facade_columns_.size()];
      const Eigen::Vector2d d = (b - a).normalized();
      const bool closed = unit() < 0.65 || k % 2 == 0;
      if (!closed) continue;
      const std::string id = "F" + std::to_string(++facade);
      addWall(id, a + 0.5 * column_ * d, b - 0.5 * column_ * d, kFacadeThickness, "facade");
      facade_walls.push_back(id);
      const double length = (b - a).norm() - column_;
      if (length > 3.0 && unit() < 0.8) {
        bim::Window window;
        window.id = "WI" + std::to_string(level.windows.size() + 1);
        window.wall = id;
        window.width = mm(length - 1.2);
        window.offset = mm(0.5 * length);
        window.sill = 0.9;
        window.height = 1.5;
        level.windows.push_back(window);
      }
    }
  }

  // The core: its outline walls, cross walls into 3–4 rooms, each but a shaft with a doorway onto
  // the floor (a gap in the core's south or north wall).
  void drawCoreRooms() {
    rooms = count(3, 4);
    std::vector<double> cuts = {core_lo_.x()};
    for (int r = 1; r < rooms; ++r)
      cuts.push_back(core_lo_.x() + core_w_ * r / rooms + uniform(-0.25, 0.25));
    cuts.push_back(core_hi_.x());
    const int shaft = count(0, rooms - 1);
    coreWall(core_lo_, {core_lo_.x(), core_hi_.y()});
    coreWall({core_hi_.x(), core_lo_.y()}, core_hi_);
    for (int r = 1; r < rooms; ++r) coreWall({cuts[r], core_lo_.y()}, {cuts[r], core_hi_.y()});
    for (double y : {core_lo_.y(), core_hi_.y()}) {
      double from = core_lo_.x();
      for (int r = 0; r < rooms; ++r) {
        const bool door = r != shaft && ((y == core_lo_.y()) == (r % 2 == 0));
        if (!door) continue;
        const double width = mm(uniform(0.9, 1.2));
        // Within its room, clear of the cross walls.
        const double mid = std::clamp(0.5 * (cuts[r] + cuts[r + 1]) + uniform(-0.3, 0.3),
                                      cuts[r] + 0.2 + 0.5 * width, cuts[r + 1] - 0.2 - 0.5 * width);
        coreWall({from, y}, {mid - 0.5 * width, y});
        from = mid + 0.5 * width;
      }
      coreWall({from, y}, {core_hi_.x(), y});
    }
  }

  // Partitions: two or three, 3–6 m long, one at an angle, each kPassage from everything.
  void drawPartitions() {
    const int wanted = count(2, 3);
    for (int attempt = 0; attempt < 400 && int(partitions.size()) < wanted; ++attempt) {
      const double length = uniform(3.0, 6.0);
      const double angle =
          partitions.empty() ? uniform(0.3, 1.2) : (unit() < 0.5 ? 0.0 : 1.5707963);
      const Eigen::Vector2d centre(uniform(2.0, slab.width - 2.0), uniform(2.0, slab.depth - 2.0));
      const Eigen::Vector2d half = 0.5 * length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      const Eigen::Vector2d a = centre - half, b = centre + half;
      if (!slab.inside(a, 2.0) || !slab.inside(b, 2.0)) continue;
      const Segment candidate{slab.place(a), slab.place(b), kPartitionThickness};
      bool clear = true;
      for (const auto& s : solids) {
        if (segmentDistance(candidate, s) < kPassage + 0.5 * (s.thickness + kPartitionThickness)) {
          clear = false;
          break;
        }
      }
      if (!clear) continue;
      const std::string id = "P" + std::to_string(partitions.size() + 1);
      addWall(id, {mm(a.x()), mm(a.y())}, {mm(b.x()), mm(b.y())}, kPartitionThickness, "partition");
      partitions.push_back(id);
    }
  }

  // On some sites the columns inside are round (cast in tubes): they give the localizer no plane
  // to hold on to. Drawn last, so that the rest of a site is the same either way.
  void roundSomeInnerColumns() {
    round_inside = unit() < 0.3;
    if (round_inside) {
      for (std::size_t k : inner_columns) level.columns[k].shape = bim::Column::Shape::kRound;
    }
  }

  Slab slab;
  std::vector<std::string> facade_walls, partitions;
  std::vector<std::size_t> inner_columns;
  int columns = 0, facade = 0, rooms = 0;
  bool round_inside = false;

 private:
  bool nearCore(const Eigen::Vector2d& p, double margin) const {
    return p.x() > core_lo_.x() - margin && p.x() < core_hi_.x() + margin &&
           p.y() > core_lo_.y() - margin && p.y() < core_hi_.y() + margin;
  }

  void addWall(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
               double thickness, const std::string& name) {
    addPlacedWall(id, slab.place(a), slab.place(b), thickness, name);
  }

  void coreWall(Eigen::Vector2d a, Eigen::Vector2d b) {
    addWall("K" + std::to_string(++core_walls_), a, b, kCoreThickness, "core");
  }

  // Square columns; inside, on some sites, round ones (roundSomeInnerColumns).
  void addColumn(const Eigen::Vector2d& c, bool inner) {
    ++columns;
    const std::size_t index = addPlacedColumn(slab.place(c), column_, false);
    if (inner) inner_columns.push_back(index);
  }

  int bays_x_ = 0, bays_y_ = 0;
  double column_ = 0.0;
  double core_w_ = 0.0, core_d_ = 0.0;
  Eigen::Vector2d core_lo_ = Eigen::Vector2d::Zero(), core_hi_ = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> facade_columns_;  // in order round the outline
  int core_walls_ = 0;
};

// As built, from a stream of its own (built_rng): a façade wall or two and maybe a partition not
// built yet.
std::vector<std::string> chooseMissingWalls(const SiteDrawing& site, std::mt19937_64& built_rng) {
  std::vector<std::string> missing;
  std::vector<std::string> open = site.facade_walls;
  std::shuffle(open.begin(), open.end(), built_rng);
  const int unbuilt = std::min<int>(int(open.size()) / 4, 1 + int(built_rng() % 2));
  for (int k = 0; k < unbuilt; ++k) missing.push_back(open[std::size_t(k)]);
  if (!site.partitions.empty() && built_rng() % 3 == 0) missing.push_back(site.partitions.back());
  return missing;
}

// Pallets on the floor, clear of everything and of each other.
std::vector<bim::Clutter> pallets(const SiteDrawing& site, std::mt19937_64& built_rng,
                                  std::uniform_real_distribution<double>& built_unit) {
  const Slab& slab = site.slab;
  std::vector<bim::Clutter> clutter;
  const int wanted = 3 + int(built_rng() % 4);
  for (int attempt = 0; attempt < 400 && int(clutter.size()) < wanted; ++attempt) {
    const Eigen::Vector2d c(slab.width * built_unit(built_rng), slab.depth * built_unit(built_rng));
    if (!slab.inside(c, 2.0)) continue;
    const Eigen::Vector2d p = slab.place(c);
    const Segment dot{p, p + Eigen::Vector2d(1e-3, 0), 0.0};
    bool clear = true;
    for (const auto& s : site.solids) {
      if (segmentDistance(dot, s) < kPassage + 0.8 + 0.5 * s.thickness) clear = false;
    }
    for (const auto& other : clutter) {
      if ((other.center.head<2>() - p).norm() < 2.5) clear = false;
    }
    if (!clear) continue;
    const double height = mm(0.4 + 1.0 * built_unit(built_rng));
    bim::Clutter box;
    box.center = {mm(p.x()), mm(p.y()), mm(0.5 * height)};
    box.size = {1.2, 1.0, height};
    box.yaw = mm(3.14159 * built_unit(built_rng));
    clutter.push_back(box);
  }
  return clutter;
}

// On 6 sites in 10 a wall is going up: a façade wall without a window or a partition, not
// missing, built from one end to 30–70 % of it, or (one in three) with a gap of 1–2 m in the
// middle. Drawn after the rest, so that the other deviations are the same either way. None when
// none is.
std::optional<bim::ShortenedWall> risingWall(const bim::Level& level,
                                             const std::vector<std::string>& missing,
                                             std::mt19937_64& built_rng,
                                             std::uniform_real_distribution<double>& built_unit) {
  std::vector<std::string> rising;
  for (const auto& wall : level.walls) {
    const bool facade_or_partition = wall.name == "facade" || wall.name == "partition";
    const bool has_window = std::any_of(level.windows.begin(), level.windows.end(),
                                        [&](const bim::Window& w) { return w.wall == wall.id; });
    const bool gone = std::find(missing.begin(), missing.end(), wall.id) != missing.end();
    if (facade_or_partition && !has_window && !gone && (wall.end - wall.start).norm() >= 2.5) {
      rising.push_back(wall.id);
    }
  }
  if (rising.empty() || !(built_unit(built_rng) < 0.6)) return std::nullopt;
  const std::string id = rising[std::size_t(built_rng() % rising.size())];
  const bim::Wall& wall = *level.findWall(id);
  // To the millimetre, never past the wall's end.
  const double length = std::floor(1000.0 * (wall.end - wall.start).norm()) / 1000.0;
  bim::ShortenedWall out{id, {}};
  if (built_rng() % 3 == 0) {
    const double gap = std::min(mm(1.0 + built_unit(built_rng)), length - 1.0);
    const double from = mm(0.5 + (length - 1.0 - gap) * built_unit(built_rng));
    out.built.push_back({0.0, from});
    out.built.push_back({mm(from + gap), length});
  } else {
    const double part = mm(length * (0.3 + 0.4 * built_unit(built_rng)));
    if (built_rng() % 2 == 0) {
      out.built.push_back({0.0, part});
    } else {
      out.built.push_back({mm(length - part), length});
    }
  }
  return out;
}

// The site as built against its plan (the plan's level, as written).
bim::AsBuilt siteAsBuilt(const GeneratorSpec& spec, const SiteDrawing& site,
                         const bim::Level& level) {
  std::mt19937_64 built_rng(spec.seed * 0xD1B54A32D192ED03ULL + 13);
  bim::AsBuilt as_built;
  as_built.missing_walls = chooseMissingWalls(site, built_rng);
  std::uniform_real_distribution<double> built_unit(0.0, 1.0);
  as_built.clutter = pallets(site, built_rng, built_unit);
  if (auto rising = risingWall(level, as_built.missing_walls, built_rng, built_unit)) {
    as_built.shortened_walls.push_back(std::move(*rising));
  }
  columnsAsBuilt(spec, site.inner_columns, level, as_built);
  return as_built;
}

}  // namespace

// Slab → columns → façade → core → partitions, then the site as built.
GeneratedBuilding generateSite(const GeneratorSpec& spec) {
  SiteDrawing site(spec);
  site.drawSlab();
  site.placeCore();
  site.drawColumns();
  site.drawFacade();
  site.drawCoreRooms();
  site.drawPartitions();
  site.roundSomeInnerColumns();

  GeneratedBuilding out;
  out.name = spec.family + "-" + std::to_string(spec.seed);
  out.as_built = siteAsBuilt(spec, site, site.level);
  // The plan lists no rooms: the core's are walls only, the floor is open.
  out.offices = 0;
  out.corridors = 0;
  char title[200];
  std::snprintf(title, sizeof title,
                "generated site: %.0f × %.0f m open floor, %d columns%s, %d façade walls, a core "
                "of %d rooms, %zu partitions, seed %llu",
                site.slab.width, site.slab.depth, site.columns,
                site.round_inside && !site.inner_columns.empty() ? " (round inside)" : "",
                site.facade, site.rooms, site.partitions.size(), (unsigned long long)spec.seed);
  bim::Plan plan;
  plan.name = title;
  plan.levels.push_back(site.level);
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
