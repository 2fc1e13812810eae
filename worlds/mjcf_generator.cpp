#include "worlds/mjcf_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "common/xml_escape.hpp"
#include "worlds/as_built.hpp"

namespace isg::worlds {

namespace {

// Enough digits for micrometres on buildings kilometres across.
std::string num(double v) {
  if (std::abs(v) < 5e-13) v = 0.0;  // no "-0"
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

std::string mjcfVector(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) {
    if (!out.empty()) out += ' ';
    out += num(v);
  }
  return out;
}

// Text for inside <!-- -->, where "--" is not allowed.
std::string xmlComment(const std::string& text) {
  std::string out = common::xmlEscape(text);
  for (std::size_t at = out.find("--"); at != std::string::npos; at = out.find("--", at)) {
    out.replace(at, 2, "- -");
  }
  return out;
}

struct Box2 {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  void add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool valid() const { return (lo.array() <= hi.array()).all(); }
};

// Writes <geom type="box"> elements: a box given by its centre, half extents and yaw about z.
class BoxWriter {
 public:
  explicit BoxWriter(std::ostringstream& out) : out_(out) {}

  void box(const std::string& name, const std::string& cls, const std::string& material,
           const Eigen::Vector3d& centre, const Eigen::Vector3d& half, double yaw) {
    out_ << "    <geom name=\"" << common::xmlEscape(name) << "\" class=\"" << cls
         << "\" material=\"" << material << "\" pos=\""
         << mjcfVector({centre.x(), centre.y(), centre.z()}) << "\" size=\""
         << mjcfVector({half.x(), half.y(), half.z()}) << "\"";
    if (std::abs(yaw) > 0.0) {
      out_ << " quat=\"" << mjcfVector({std::cos(0.5 * yaw), 0.0, 0.0, std::sin(0.5 * yaw)})
           << "\"";
    }
    out_ << "/>\n";
  }

  // A box spanning [s0, s1] along a wall's axis, the wall's thickness (or `thickness`) across,
  // and [z0, z1] in height.
  void wallPiece(const std::string& name, const std::string& material, const bim::WallGeometry& g,
                 double s0, double s1, double thickness, double z0, double z1) {
    if (s1 - s0 < 1e-6 || z1 - z0 < 1e-6) return;
    const Eigen::Vector2d c = g.pointAt(0.5 * (s0 + s1));
    box(name, "building", material, {c.x(), c.y(), 0.5 * (z0 + z1)},
        {0.5 * (s1 - s0), 0.5 * thickness, 0.5 * (z1 - z0)}, std::atan2(g.axis.y(), g.axis.x()));
  }

 private:
  std::ostringstream& out_;
};

// A horizontal slab [lo, hi] × [z0, z1] with rectangular holes: one box when it has none (so a
// plan without stairs writes the world it always did), else the solid cells of the grid the
// holes' edges cut it into, merged along x into as few boxes as that gives.
void writeSlab(BoxWriter& writer, const std::string& name, const std::string& cls,
               const std::string& material, const Eigen::Vector2d& centre,
               const Eigen::Vector2d& half, double z0, double z1, const std::vector<Box2>& holes) {
  const double zc = 0.5 * (z0 + z1);
  const double zh = 0.5 * (z1 - z0);
  if (holes.empty()) {
    writer.box(name, cls, material, {centre.x(), centre.y(), zc}, {half.x(), half.y(), zh}, 0.0);
    return;
  }
  Box2 slab;
  slab.add(centre - half);
  slab.add(centre + half);
  std::vector<double> xs{slab.lo.x(), slab.hi.x()}, ys{slab.lo.y(), slab.hi.y()};
  for (const auto& hole : holes) {
    for (double x : {hole.lo.x(), hole.hi.x()})
      xs.push_back(std::clamp(x, slab.lo.x(), slab.hi.x()));
    for (double y : {hole.lo.y(), hole.hi.y()})
      ys.push_back(std::clamp(y, slab.lo.y(), slab.hi.y()));
  }
  for (auto* cuts : {&xs, &ys}) {
    std::sort(cuts->begin(), cuts->end());
    cuts->erase(std::unique(cuts->begin(), cuts->end(),
                            [](double a, double b) { return std::abs(a - b) < 1e-6; }),
                cuts->end());
  }
  auto open = [&](double x, double y) {
    for (const auto& hole : holes) {
      if (x > hole.lo.x() && x < hole.hi.x() && y > hole.lo.y() && y < hole.hi.y()) return true;
    }
    return false;
  };
  int piece = 0;
  for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
    const double y0 = ys[j], y1 = ys[j + 1];
    std::size_t i = 0;
    while (i + 1 < xs.size()) {
      if (open(0.5 * (xs[i] + xs[i + 1]), 0.5 * (y0 + y1))) {
        ++i;
        continue;
      }
      std::size_t k = i + 1;
      while (k + 1 < xs.size() && !open(0.5 * (xs[k] + xs[k + 1]), 0.5 * (y0 + y1))) ++k;
      writer.box(name + "/" + std::to_string(piece++), cls, material,
                 {0.5 * (xs[i] + xs[k]), 0.5 * (y0 + y1), zc},
                 {0.5 * (xs[k] - xs[i]), 0.5 * (y1 - y0), zh}, 0.0);
      i = k;
    }
  }
}

// The stairwells that open a level's floor (flights up to it) and its ceiling (flights up from
// it): the axis-aligned box of each flight's opening (bim::StairGeometry::openingFootprint),
// which opens a diagonal flight's slab a little wider than the flight.
struct Stairwells {
  std::vector<Box2> floor;
  std::vector<Box2> ceiling;
};

Stairwells stairwellsOf(const bim::Plan& plan, const bim::Level& level) {
  Stairwells wells;
  for (const auto& from : plan.levels) {
    for (const auto& stair : from.stairs) {
      const bim::Level* to = plan.findLevel(stair.to);
      if (to == nullptr) continue;
      const bim::Level& lower = from.elevation < to->elevation ? from : *to;
      const bim::Level& upper = from.elevation < to->elevation ? *to : from;
      if (&lower != &level && &upper != &level) continue;
      Box2 box;
      for (const auto& p : bim::computeStairGeometry(stair, from, *to).openingFootprint()) {
        box.add(p);
      }
      (&upper == &level ? wells.floor : wells.ceiling).push_back(box);
    }
  }
  return wells;
}

// A flight's steps: solid blocks from the lower floor up to each tread.
void writeStairs(BoxWriter& writer, const bim::Plan& plan, const bim::Level& level) {
  for (const auto& stair : level.stairs) {
    const bim::Level* to = plan.findLevel(stair.to);
    if (to == nullptr) continue;
    const bim::StairGeometry g = bim::computeStairGeometry(stair, level, *to);
    const double floor = std::min(g.z_start, g.z_end);
    const double yaw = std::atan2(g.axis.y(), g.axis.x());
    for (int k = 0; k < g.steps; ++k) {
      const auto step = g.step(k);
      const Eigen::Vector2d c = stair.start + 0.5 * (step.s0 + step.s1) * g.axis;
      writer.box("stair/" + stair.id + "/" + std::to_string(k), "building", "stair",
                 {c.x(), c.y(), 0.5 * (floor + step.top)},
                 {0.5 * (step.s1 - step.s0), 0.5 * stair.width, 0.5 * (step.top - floor)}, yaw);
    }
  }
}

bool contains(const std::vector<std::string>& ids, const std::string& id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

// Vertical room each slab may take: a slab never reaches into another level's space. Where a
// level starts exactly at the ceiling of the one below, ceiling and floor are 0.5 mm each.
struct SlabHeights {
  double ceiling_top;
  double floor_bottom;
};

SlabHeights slabHeights(const bim::Plan& plan, const bim::Level& level, double slab) {
  constexpr double kMinSlab = 5e-4;
  const double ceiling = level.elevation + level.height;
  double above = std::numeric_limits<double>::infinity();
  double below = std::numeric_limits<double>::infinity();
  for (const auto& other : plan.levels) {
    if (&other == &level) continue;
    if (other.elevation >= ceiling) above = std::min(above, other.elevation - ceiling);
    const double other_ceiling = other.elevation + other.height;
    if (other_ceiling <= level.elevation) below = std::min(below, level.elevation - other_ceiling);
  }
  return {ceiling + std::min(slab, std::max(0.5 * above, kMinSlab)),
          level.elevation - std::min(slab, std::max(0.5 * below, kMinSlab))};
}

void writeLevel(std::ostringstream& out, const bim::Plan& plan, const bim::Level& plan_level,
                const bim::AsBuilt& as_built, const WorldOptions& options, Box2& world_box) {
  const bim::Level level = asBuiltLevel(plan_level, as_built);
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  BoxWriter writer(out);
  out << "    <!-- level " << xmlComment(level.id) << " -->\n";

  Box2 box;
  for (const auto& g : geometry.walls) {
    for (const auto& p : g.footprint()) box.add(p);
  }
  for (const auto& room : level.rooms) {
    for (const auto& p : room.outline) box.add(p);
  }
  for (const auto& column : level.columns) {
    for (const auto& p : bim::columnFootprint(column)) box.add(p);
  }
  world_box.add(box.lo);
  world_box.add(box.hi);

  const SlabHeights slabs = slabHeights(plan, level, options.slab_thickness);
  const Stairwells wells = stairwellsOf(plan, plan_level);
  const Eigen::Vector2d centre = 0.5 * (box.lo + box.hi);
  const Eigen::Vector2d half = 0.5 * (box.hi - box.lo);
  const Eigen::Vector2d floor_half = half.array() + options.floor_margin;
  writeSlab(writer, "floor/" + level.id, "building", "floor", centre, floor_half,
            slabs.floor_bottom, level.elevation, wells.floor);
  if (options.ceilings) {
    const double ceiling = level.elevation + level.height;
    writeSlab(writer, "ceiling/" + level.id, "ceiling", "ceiling", centre, half, ceiling,
              slabs.ceiling_top, wells.ceiling);
  }
  writeStairs(writer, plan, plan_level);

  for (std::size_t w = 0; w < geometry.walls.size(); ++w) {
    const bim::WallGeometry& g = geometry.walls[w];
    const bim::Wall& wall = *g.wall;
    if (g.column) {  // a rectangular column: one box, no openings
      writer.wallPiece("column/" + wall.id, "wall", g, -g.extend_start, g.length + g.extend_end,
                       wall.thickness, level.elevation + wall.base, level.elevation + wall.height);
      continue;
    }
    const bool extra = wall.id.rfind("extra", 0) == 0 && plan_level.findWall(wall.id) == nullptr;
    const std::string material = extra ? "extra_wall" : "wall";
    const double z0 = level.elevation + wall.base;
    const double z1 = level.elevation + wall.height;
    // Each opening leaves wall below it (windows) and above it (a lintel, when lower than the
    // wall).
    double s = -g.extend_start;
    int piece = 0;
    for (const bim::WallOpening& opening : bim::wallOpenings(level, wall.id)) {
      const double lo = opening.lo, hi = opening.hi;
      if (lo - s >= 1e-6) {
        writer.wallPiece("wall/" + wall.id + "/" + std::to_string(piece++), material, g, s, lo,
                         wall.thickness, z0, z1);
      }
      if (opening.bottom > 0.0) {
        writer.wallPiece("wall/" + wall.id + "/sill/" + opening.id, material, g, lo, hi,
                         wall.thickness, z0, z0 + opening.bottom);
      }
      writer.wallPiece("wall/" + wall.id + "/lintel/" + opening.id, material, g, lo, hi,
                       wall.thickness, z0 + opening.top, z1);
      if (opening.door != nullptr && contains(as_built.closed_doors, opening.id)) {
        writer.wallPiece("door/" + opening.id, "door", g, lo, hi,
                         std::min(options.door_leaf_thickness, wall.thickness), z0,
                         z0 + opening.top);
      }
      s = hi;
    }
    writer.wallPiece("wall/" + wall.id + "/" + std::to_string(piece), material, g, s,
                     g.length + g.extend_end, wall.thickness, z0, z1);
  }

  for (const auto& column : level.columns) {
    if (!column.round()) continue;
    const double z0 = level.elevation + column.base, z1 = level.elevation + column.height;
    out << "    <geom name=\"column/" << common::xmlEscape(column.id)
        << "\" class=\"building\" type=\"cylinder\" material=\"wall\" pos=\""
        << mjcfVector({column.center.x(), column.center.y(), 0.5 * (z0 + z1)}) << "\" size=\""
        << mjcfVector({column.radius(), 0.5 * (z1 - z0)}) << "\"/>\n";
  }

  for (std::size_t k = 0; k < as_built.clutter.size(); ++k) {
    const auto& clutter = as_built.clutter[k];
    if (clutter.level != level.id) continue;
    writer.box("clutter/" + std::to_string(k), "building", "clutter",
               {clutter.center.x(), clutter.center.y(), level.elevation + clutter.center.z()},
               0.5 * clutter.size, clutter.yaw);
  }

  for (const auto& room : level.rooms) {
    const Eigen::Vector2d c = bim::centroid(room.outline);
    out << "    <site name=\"room/" << common::xmlEscape(room.id) << "\" pos=\""
        << mjcfVector({c.x(), c.y(), level.elevation + 0.01}) << "\" size=\"0.08\" group=\""
        << kBuildingGroup << "\" rgba=\".2 .5 .9 .6\"/>\n";
  }
}

}  // namespace

std::string generateMjcf(const bim::Plan& plan, const bim::AsBuilt& as_built,
                         const WorldOptions& options) {
  std::ostringstream body;
  Box2 box;
  double z_lo = std::numeric_limits<double>::infinity();
  double z_hi = -std::numeric_limits<double>::infinity();
  for (const auto& level : plan.levels) {
    writeLevel(body, plan, level, as_built, options, box);
    z_lo = std::min(z_lo, level.elevation);
    z_hi = std::max(z_hi, level.elevation + level.height);
  }
  const bool has_stairs = std::any_of(plan.levels.begin(), plan.levels.end(),
                                      [](const bim::Level& l) { return !l.stairs.empty(); });
  const Eigen::Vector2d centre = 0.5 * (box.lo + box.hi);
  const Eigen::Vector2d size = box.hi - box.lo;
  const double extent = std::max({size.x(), size.y(), z_hi - z_lo, 1.0});
  // A camera straight above that sees the whole footprint, with a 5 % margin, in a 16:9 picture
  // with its 45° vertical field of view.
  const double top_height =
      z_hi + 0.55 * std::max(size.y(), size.x() / (16.0 / 9.0)) / std::tan(std::numbers::pi / 8.0);

  std::ostringstream out;
  out << "<!-- Generated by isg world from "
      << xmlComment(plan.source.empty() ? plan.name : plan.source)
      << ". Edit the plan, not this file. -->\n";
  out << "<mujoco model=\"" << common::xmlEscape(plan.name) << "\">\n"
      << "  <compiler autolimits=\"true\" angle=\"radian\"/>\n"
      << "  <option timestep=\"0.002\"/>\n"
      << "  <statistic center=\"" << mjcfVector({centre.x(), centre.y(), 0.5 * (z_lo + z_hi)})
      << "\" extent=\"" << num(extent) << "\"/>\n"
      << "  <visual>\n"
      << "    <global offwidth=\"1920\" offheight=\"1080\"/>\n"
      << "    <headlight ambient=\".35 .35 .35\" diffuse=\".45 .45 .45\" specular=\"0 0 0\"/>\n"
      << "    <quality shadowsize=\"4096\"/>\n"
      << "  </visual>\n"
      << "  <asset>\n"
      << "    <texture name=\"floor_grid\" type=\"2d\" builtin=\"checker\" rgb1=\".78 .76 .72\" "
         "rgb2=\".70 .68 .64\" width=\"512\" height=\"512\"/>\n"
      << "    <material name=\"floor\" texture=\"floor_grid\" texrepeat=\"1 1\" "
         "texuniform=\"true\"/>\n"
      << "    <material name=\"wall\" rgba=\".92 .90 .86 1\"/>\n"
      << "    <material name=\"extra_wall\" rgba=\".88 .62 .50 1\"/>\n"
      << "    <material name=\"ceiling\" rgba=\".96 .96 .96 .2\"/>\n"
      << "    <material name=\"door\" rgba=\".55 .36 .22 1\"/>\n"
      << "    <material name=\"clutter\" rgba=\".36 .47 .62 1\"/>\n"
      << (has_stairs ? "    <material name=\"stair\" rgba=\".80 .78 .74 1\"/>\n" : "")
      << "  </asset>\n"
      << "  <default>\n"
      << "    <default class=\"building\">\n"
      << "      <geom type=\"box\" group=\"" << kBuildingGroup << "\"/>\n"
      << "    </default>\n"
      << "    <default class=\"ceiling\">\n"
      << "      <geom type=\"box\" group=\"" << kCeilingGroup << "\"/>\n"
      << "    </default>\n"
      << "  </default>\n"
      << "  <worldbody>\n"
      << "    <light name=\"sun\" directional=\"true\" castshadow=\"false\" pos=\""
      << mjcfVector({centre.x(), centre.y(), z_hi + 10.0})
      << "\" dir=\"0.3 0.2 -1\" diffuse=\".5 .5 .5\"/>\n"
      << "    <camera name=\"top\" pos=\"" << mjcfVector({centre.x(), centre.y(), top_height})
      << "\" xyaxes=\"1 0 0 0 1 0\" fovy=\"45\"/>\n"
      << body.str() << options.extra_worldbody << "  </worldbody>\n"
      << "</mujoco>\n";
  return out.str();
}

}  // namespace isg::worlds
