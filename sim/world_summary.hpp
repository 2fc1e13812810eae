#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "bim/scenario.hpp"
#include "sim/mujoco_world.hpp"

namespace isg::sim {

// What a generated world contains and how it behaves in MuJoCo: the main job's report until the
// localizer exists, and a quick check that a plan became the building it describes.
struct RoomProbe {
  std::string room;
  std::string name;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // room centroid, 1.2 m above the floor
  int rays = 0;
  int hits = 0;           // rays that hit the building
  double nearest = -1.0;  // distance to the nearest hit, metres
  std::string nearest_geom;
};

struct WorldSummary {
  std::string model_name;
  int bodies = 0;
  int geoms = 0;
  int sites = 0;
  std::map<std::string, int> geoms_by_kind;  // "wall", "lintel", "door", "floor", ...
  int steps = 0;
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  std::vector<RoomProbe> rooms;
};

// Steps the world `steps` times and casts `rays_per_room` horizontal rays from every room of the
// robot's level.
WorldSummary summarizeWorld(const bim::Scenario& scenario, MujocoWorld& world, int steps,
                            int rays_per_room = 72);

std::string formatSummary(const WorldSummary& summary);

}  // namespace isg::sim
