#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace isg::sim {

// A ray caster over a compiled MuJoCo model's geoms that returns what
//   mj_ray(m, d, origin, direction, groups, flg_static = 1, bodyexclude = -1, &geom)
// returns — the same geom and the same distance — many times faster on building worlds.
//
// MuJoCo 2.2.2's mj_ray tests every geom of the model for every ray. Here the geoms welded to
// the world (the building) go into a bounding volume hierarchy built once, and each ray visits
// only the boxes along its way, nearest first, stopping as soon as nothing nearer can be hit.
// Slabs that span the building are tested directly first: their hit bounds the search; long
// walls enter the hierarchy as several short fragments.
// Boxes are intersected in their own frame exactly as MuJoCo does (slab test); other geom types
// and geoms that move (the robot, if its group is asked for) are handed to mju_rayGeom /
// mj_rayMesh. Ties are broken by the lower geom id, as mj_ray's loop does.
class RayCaster {
 public:
  // Builds the hierarchy from the geoms' current poses in `data` (call mj_kinematics first).
  // `groups`: bit g set = geom group g is seen.
  RayCaster(const mjModel& model, const mjData& data, unsigned groups);

  struct Hit {
    double distance = -1.0;
    int geom = -1;
  };
  // `direction` must be a unit vector for the distance to be metres (as for mj_ray).
  std::optional<Hit> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

  int staticGeomCount() const { return int(boxes_.size() + large_.size() + others_.size()); }
  int nodeCount() const { return int(nodes_.size()); }
  int largeCount() const { return int(large_.size()); }

 private:
  struct Box {
    Eigen::Vector3d pos;
    Eigen::Matrix3d mat;  // columns: the box's axes in world coordinates
    Eigen::Vector3d half;
    int geom;
  };
  struct Node {
    Eigen::Vector3d lo, hi;
    int first;  // leaf: first primitive index; inner: index of the right child (left = this + 1)
    int count;  // leaf: number of primitives (> 0); inner: 0
  };
  struct Pending {
    int node;
    double entry;
  };

  void build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& lo,
             const std::vector<Eigen::Vector3d>& hi, int begin, int end);
  double intersectBox(const Box& box, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction) const;
  double intersectOther(int geom, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction) const;

  const mjModel* model_;
  const mjData* data_;
  std::vector<Box> boxes_;  // static boxes
  // The hierarchy's leaves refer to boxes through fragments: a long wall is cut into pieces of
  // at most kFragmentLength along its length, each with its own bounds, so that no node is as long
  // as the building's longest wall. The whole box is tested whenever a fragment is reached.
  std::vector<int> fragment_box_;  // box index per fragment, in hierarchy leaf order
  // Static boxes that span much of the building (floor and ceiling slabs): in a hierarchy they
  // would make every node around them building-sized, so they are tested first, directly; their
  // hit then bounds the search through the hierarchy.
  std::vector<Box> large_;
  std::vector<Node> nodes_;
  std::vector<int> others_;  // static non-box geoms that are seen (planes, meshes, ...)
  std::vector<int> moving_;  // geoms not welded to the world that are seen: tested every ray
};

// Whether mj_ray would consider this geom at all for these groups (static geoms included, no
// body excluded): not invisible (alpha 0), in a group that is seen (planes ignore groups).
bool rayConsidersGeom(const mjModel& model, int geom, unsigned groups);

}  // namespace isg::sim
