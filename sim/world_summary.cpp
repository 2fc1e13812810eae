#include "sim/world_summary.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "bim/polygon.hpp"
#include "common/plural.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::sim {

namespace {

// "wall/W3/lintel/D1" → "lintel", "wall/W3/0" → "wall", "floor/L0" → "floor".
std::string geomKind(const std::string& name) {
  if (name.find("/lintel/") != std::string::npos) return "lintel";
  const auto slash = name.find('/');
  return slash == std::string::npos ? (name.empty() ? "unnamed" : name) : name.substr(0, slash);
}

}  // namespace

WorldSummary summarizeWorld(const bim::Scenario& scenario, MujocoWorld& world, int steps,
                            int rays_per_room) {
  const mjModel& m = world.model();
  WorldSummary summary;
  summary.model_name = scenario.plan.name;
  summary.bodies = m.nbody;
  summary.geoms = m.ngeom;
  summary.sites = m.nsite;
  for (int g = 0; g < m.ngeom; ++g) ++summary.geoms_by_kind[geomKind(world.geomName(g))];

  const auto start = std::chrono::steady_clock::now();
  world.step(steps);
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.steps = steps;
  summary.sim_seconds = world.time();

  const bim::Level* level = scenario.plan.findLevel(scenario.robot.level);
  for (const auto& room : level->rooms) {
    RoomProbe probe;
    probe.room = room.id;
    probe.name = room.name;
    const Eigen::Vector2d c = bim::centroid(room.outline);
    probe.origin = {c.x(), c.y(), level->elevation + 1.2};
    probe.rays = rays_per_room;
    for (int k = 0; k < rays_per_room; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / rays_per_room;
      const auto hit = world.ray(probe.origin, {std::cos(angle), std::sin(angle), 0.0},
                                 1u << worlds::kBuildingGroup);
      if (!hit) continue;
      ++probe.hits;
      if (probe.nearest < 0 || hit->distance < probe.nearest) {
        probe.nearest = hit->distance;
        probe.nearest_geom = world.geomName(hit->geom);
      }
    }
    summary.rooms.push_back(probe);
  }
  return summary;
}

std::string formatSummary(const WorldSummary& s) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "world \"%s\": %s, %s, %s\n", s.model_name.c_str(),
                common::counted(s.bodies, "body", "bodies").c_str(),
                common::counted(s.geoms, "geom").c_str(), common::counted(s.sites, "site").c_str());
  out += line;
  out += "  geoms by kind:";
  for (const auto& [kind, count] : s.geoms_by_kind) {
    std::snprintf(line, sizeof line, " %s %d,", kind.c_str(), count);
    out += line;
  }
  if (out.back() == ',') out.pop_back();
  out += "\n";
  std::snprintf(line, sizeof line,
                "  stepped %d times: %.3f s of simulated time in %.3f s (%.0fx real time)\n",
                s.steps, s.sim_seconds, s.wall_seconds,
                s.wall_seconds > 0 ? s.sim_seconds / s.wall_seconds : 0.0);
  out += line;
  out += "  rooms (horizontal rays from the centroid, 1.2 m above the floor):\n";
  for (const auto& r : s.rooms) {
    std::snprintf(line, sizeof line,
                  "    %-6s %-28s %3d/%d rays hit the building; nearest %-22s at %.3f m\n",
                  r.room.c_str(), ("\"" + r.name + "\"").c_str(), r.hits, r.rays,
                  r.nearest_geom.c_str(), r.nearest);
    out += line;
  }
  return out;
}

}  // namespace isg::sim
