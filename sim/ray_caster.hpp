#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cmath>
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
// Boxes are intersected in their own frame exactly as MuJoCo does (slab test), static cylinders
// (round columns) go into the hierarchy by their bounding boxes and are tested by MuJoCo's own
// cylinder test; other geom types
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
    // Keeps the nearer of this and (x, geom); equal distances go to the lower geom id, as in
    // mj_ray's loop over geoms. Every caster decides through this one rule.
    void consider(double x, int candidate) {
      if (x >= 0 && (distance < 0 || x < distance || (x == distance && candidate < geom))) {
        distance = x;
        geom = candidate;
      }
    }
  };
  // `direction` must be a unit vector for the distance to be metres (as for mj_ray).
  std::optional<Hit> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

  friend class ScanCaster;

  int staticGeomCount() const { return int(boxes_.size() + large_.size() + others_.size()); }
  int nodeCount() const { return int(nodes_.size()); }
  int largeCount() const { return int(large_.size()); }

 private:
  struct Box {
    Eigen::Vector3d pos;
    Eigen::Matrix3d mat;  // columns: the box's axes in world coordinates
    Eigen::Vector3d half;
    int geom;
    bool axis_aligned;      // mat is the identity
    bool upright;           // turned about z only (every wall): the z row of mat is (0, 0, 1)
    bool cylinder = false;  // a cylinder of radius half.x and half-height half.z, not a box
  };
  struct Node {
    Eigen::Vector3d lo, hi;
    int first =
        0;  // leaf: first primitive index; inner: index of the right child (left = this + 1)
    int count = 0;  // leaf: number of primitives (> 0); inner: 0
  };
  struct Pending {
    int node;
    double entry;
  };

  void build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& lo,
             const std::vector<Eigen::Vector3d>& hi, int begin, int end);
  double intersectBox(const Box& box, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction) const;
  // The same result for an unrotated slab seen from above or below, in a few operations.
  double intersectSlab(const Box& box, const Eigen::Vector3d& origin,
                       const Eigen::Vector3d& direction) const;
  double intersectOther(int geom, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction) const;
  // intersectBox, or for a cylinder MuJoCo's own cylinder test.
  double intersectSolid(const Box& box, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction) const {
    return box.cylinder ? intersectOther(box.geom, origin, direction)
                        : intersectBox(box, origin, direction);
  }
  // The geoms every ray tests whatever its direction: building-wide slabs, non-box static geoms
  // and moving geoms.
  void castAlwaysTested(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                        Hit& best) const;

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

// The exact tests, inline: they are the inner loop of every caster.

inline double RayCaster::intersectBox(const Box& box, const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const {
  // The ray in the box's frame, then MuJoCo's face test (the box case of mju_rayGeom): the
  // nearest face crossing that lands within its face. Only three faces can give it: the faces
  // the ray enters through when it starts outside, the faces it leaves through when inside.
  const Eigen::Vector3d d = origin - box.pos;
  Eigen::Vector3d p, v;
  if (box.upright) {
    const auto& R = box.mat;
    p << R(0, 0) * d[0] + R(1, 0) * d[1], R(0, 1) * d[0] + R(1, 1) * d[1], d[2];
    v << R(0, 0) * direction[0] + R(1, 0) * direction[1],
        R(0, 1) * direction[0] + R(1, 1) * direction[1], direction[2];
  } else {
    p = box.mat.transpose() * d;
    v = box.mat.transpose() * direction;
  }
  const bool inside = std::abs(p[0]) <= box.half[0] && std::abs(p[1]) <= box.half[1] &&
                      std::abs(p[2]) <= box.half[2];
  double best = -1.0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v[i]) <= mjMINVAL) continue;
    const int side = (v[i] > 0) == inside ? 1 : -1;
    const double x = (side * box.half[i] - p[i]) / v[i];
    if (x < 0) continue;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (std::abs(p[j] + x * v[j]) <= box.half[j] && std::abs(p[k] + x * v[k]) <= box.half[k] &&
        (best < 0 || x < best)) {
      best = x;
    }
  }
  return best;
}

inline double RayCaster::intersectSlab(const Box& box, const Eigen::Vector3d& origin,
                                       const Eigen::Vector3d& direction) const {
  if (!box.axis_aligned) return intersectBox(box, origin, direction);
  const double pz = origin.z() - box.pos.z();
  const double vz = direction.z();
  // From above (below) the slab, a ray that leaves it behind never hits it.
  if (pz >= box.half.z() && vz >= 0) return -1.0;
  if (pz <= -box.half.z() && vz <= 0) return -1.0;
  if (std::abs(pz) < box.half.z() || std::abs(vz) <= mjMINVAL) {
    return intersectBox(box, origin, direction);
  }
  // Coming down onto the top face (or up onto the bottom one): if it lands within the face that
  // is the nearest face hit, since z changes monotonically along the ray.
  const double face = pz > 0 ? box.half.z() : -box.half.z();
  const double x = (face - pz) / vz;
  const double px = origin.x() - box.pos.x() + x * direction.x();
  const double py = origin.y() - box.pos.y() + x * direction.y();
  if (std::abs(px) <= box.half.x() && std::abs(py) <= box.half.y()) return x;
  // Landing beside the face (a slab that covers only part of the building: on D3 by hand two rays
  // in five): the ray is within the slab's height only while it goes through it, over
  // 2 half_z / |v_z| of its length, and it misses unless it comes within reach of the footprint
  // meanwhile. Decided here with a margin of 1e-9 of the terms' size (rounding is ~1e-16 of it),
  // so the face test, whose answer this is bit for bit, runs only for rays that may hit a side.
  const double through = 2.0 * box.half.z() / std::abs(vz);
  const double reach_x = std::abs(direction.x()) * through;
  const double reach_y = std::abs(direction.y()) * through;
  if (std::abs(px) > box.half.x() + reach_x + 1e-9 * (std::abs(px) + reach_x) + 1e-12 ||
      std::abs(py) > box.half.y() + reach_y + 1e-9 * (std::abs(py) + reach_y) + 1e-12) {
    return -1.0;
  }
  return intersectBox(box, origin, direction);
}

inline void RayCaster::castAlwaysTested(const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& direction, Hit& best) const {
  for (const Box& box : large_) best.consider(intersectSlab(box, origin, direction), box.geom);
  for (int g : others_) best.consider(intersectOther(g, origin, direction), g);
  for (int g : moving_) best.consider(intersectOther(g, origin, direction), g);
}

// Whether mj_ray would consider this geom at all for these groups (static geoms included, no
// body excluded): not invisible (alpha 0), in a group that is seen (planes ignore groups).
bool rayConsidersGeom(const mjModel& model, int geom, unsigned groups);

}  // namespace isg::sim
