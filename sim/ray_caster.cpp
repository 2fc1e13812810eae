#include "sim/ray_caster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace isg::sim {

namespace {

constexpr int kLeafSize = 2;
constexpr double kFragmentLength = 2.0;  // metres
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Entry distance of the ray into an axis-aligned box, or +inf when it misses (or only behind).
inline double slabEntry(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& inverse,
                        double limit) {
  double t0 = 0.0;
  double t1 = limit;
  for (int i = 0; i < 3; ++i) {
    double a = (lo[i] - origin[i]) * inverse[i];
    double b = (hi[i] - origin[i]) * inverse[i];
    if (a > b) std::swap(a, b);
    // NaN (0 · inf, the ray on a slab's boundary plane) must not cull: keep the interval.
    if (a == a) t0 = std::max(t0, a);
    if (b == b) t1 = std::min(t1, b);
    if (t0 > t1) return kInfinity;
  }
  return t0;
}

}  // namespace

bool rayConsidersGeom(const mjModel& m, int geom, unsigned groups) {
  const int material = m.geom_matid[geom];
  if (material < 0 && m.geom_rgba[4 * geom + 3] == 0) return false;
  if (material >= 0 && m.mat_rgba[4 * material + 3] == 0) return false;
  if (m.geom_type[geom] == mjGEOM_PLANE) return true;  // mj_ray ignores groups for planes
  const int group = std::clamp(m.geom_group[geom], 0, mjNGROUP - 1);
  return (groups >> group) & 1u;
}

RayCaster::RayCaster(const mjModel& model, const mjData& data, unsigned groups)
    : model_(&model), data_(&data) {
  std::vector<Box> boxes;
  std::vector<Eigen::Vector3d> lo, hi;
  Eigen::Vector3d scene_lo = Eigen::Vector3d::Constant(kInfinity), scene_hi = -scene_lo;
  for (int g = 0; g < model.ngeom; ++g) {
    if (!rayConsidersGeom(model, g, groups)) continue;
    const bool is_static = model.body_weldid[model.geom_bodyid[g]] == 0;
    if (!is_static) {
      moving_.push_back(g);
      continue;
    }
    const int type = model.geom_type[g];
    if (type != mjGEOM_BOX && type != mjGEOM_CYLINDER) {
      others_.push_back(g);
      continue;
    }
    Box box;
    box.pos = Eigen::Map<const Eigen::Vector3d>(data.geom_xpos + 3 * g);
    // geom_xmat is row-major: its rows are the world axes in geom coordinates, its columns the
    // geom's axes in world coordinates.
    box.mat =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data.geom_xmat + 9 * g);
    const double* size = model.geom_size + 3 * g;
    // A cylinder (a round column) enters the hierarchy as the box around it, its own axis z.
    box.cylinder = type == mjGEOM_CYLINDER;
    box.half = box.cylinder ? Eigen::Vector3d(size[0], size[0], size[1])
                            : Eigen::Vector3d(size[0], size[1], size[2]);
    box.geom = g;
    box.axis_aligned = box.mat == Eigen::Matrix3d::Identity();
    box.upright = box.mat(2, 2) == 1.0 && box.mat(2, 0) == 0.0 && box.mat(2, 1) == 0.0 &&
                  box.mat(0, 2) == 0.0 && box.mat(1, 2) == 0.0;
    const Eigen::Vector3d extent = box.mat.cwiseAbs() * box.half;
    // A hair larger than the box, so that rounding never culls a box the exact test would hit.
    const Eigen::Vector3d pad = 1e-9 * (Eigen::Vector3d::Ones() + extent + box.pos.cwiseAbs());
    lo.push_back(box.pos - extent - pad);
    hi.push_back(box.pos + extent + pad);
    scene_lo = scene_lo.cwiseMin(lo.back());
    scene_hi = scene_hi.cwiseMax(hi.back());
    boxes.push_back(box);
  }
  // Boxes wider than a quarter of the scene both in x and in y are slabs: tested directly.
  const Eigen::Vector3d scene = scene_hi - scene_lo;
  for (std::size_t i = 0; i < boxes.size();) {
    const Eigen::Vector3d size = hi[i] - lo[i];
    if (boxes.size() > 8 && !boxes[i].cylinder && size.x() > 0.25 * scene.x() &&
        size.y() > 0.25 * scene.y()) {
      large_.push_back(boxes[i]);
      boxes.erase(boxes.begin() + i);
      lo.erase(lo.begin() + i);
      hi.erase(hi.begin() + i);
    } else {
      ++i;
    }
  }
  boxes_ = std::move(boxes);
  std::vector<Eigen::Vector3d> fragment_lo, fragment_hi;
  std::vector<int> fragment_box;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    // Walls are long horizontally: cut along the longer of x and y.
    const Eigen::Vector3d size = hi[i] - lo[i];
    const int axis = size.x() >= size.y() ? 0 : 1;
    const double length = size[axis];
    const int pieces = std::max(1, int(std::ceil(length / kFragmentLength)));
    for (int k = 0; k < pieces; ++k) {
      Eigen::Vector3d a = lo[i], b = hi[i];
      a[axis] = lo[i][axis] + length * k / pieces;
      b[axis] = k + 1 == pieces ? hi[i][axis] : lo[i][axis] + length * (k + 1) / pieces;
      fragment_lo.push_back(a);
      fragment_hi.push_back(b);
      fragment_box.push_back(int(i));
    }
  }
  std::vector<int> order(fragment_box.size());
  std::iota(order.begin(), order.end(), 0);
  if (!order.empty()) build(order, fragment_lo, fragment_hi, 0, int(order.size()));
  fragment_box_.reserve(order.size());
  for (int f : order) fragment_box_.push_back(fragment_box[f]);
}

void RayCaster::build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& lo,
                      const std::vector<Eigen::Vector3d>& hi, int begin, int end) {
  Node node;
  node.lo = Eigen::Vector3d::Constant(kInfinity);
  node.hi = -node.lo;
  Eigen::Vector3d centre_lo = node.lo, centre_hi = node.hi;
  for (int i = begin; i < end; ++i) {
    node.lo = node.lo.cwiseMin(lo[order[i]]);
    node.hi = node.hi.cwiseMax(hi[order[i]]);
    const Eigen::Vector3d c = 0.5 * (lo[order[i]] + hi[order[i]]);
    centre_lo = centre_lo.cwiseMin(c);
    centre_hi = centre_hi.cwiseMax(c);
  }
  const int index = int(nodes_.size());
  nodes_.push_back(node);
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return;
  }
  // Split by the surface area heuristic over 16 bins of box centres per axis: the split that
  // minimises (area × count) of the two halves. Building walls are long and thin, and a median
  // split would put crossing walls into the same building-sized nodes.
  auto area = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d d = (b - a).cwiseMax(0.0);
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  };
  constexpr int kBins = 16;
  double best_cost = kInfinity;
  int best_axis = -1;
  double best_split = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double span = centre_hi[axis] - centre_lo[axis];
    if (span <= 0) continue;
    std::array<Eigen::Vector3d, kBins> bin_lo, bin_hi;
    std::array<int, kBins> bin_count{};
    bin_lo.fill(Eigen::Vector3d::Constant(kInfinity));
    bin_hi.fill(Eigen::Vector3d::Constant(-kInfinity));
    for (int i = begin; i < end; ++i) {
      const double c = 0.5 * (lo[order[i]][axis] + hi[order[i]][axis]);
      const int b = std::min(kBins - 1, int(kBins * (c - centre_lo[axis]) / span));
      ++bin_count[b];
      bin_lo[b] = bin_lo[b].cwiseMin(lo[order[i]]);
      bin_hi[b] = bin_hi[b].cwiseMax(hi[order[i]]);
    }
    for (int split = 1; split < kBins; ++split) {
      Eigen::Vector3d l_lo = Eigen::Vector3d::Constant(kInfinity), l_hi = -l_lo;
      Eigen::Vector3d r_lo = l_lo, r_hi = l_hi;
      int l_count = 0, r_count = 0;
      for (int b = 0; b < split; ++b) {
        l_lo = l_lo.cwiseMin(bin_lo[b]);
        l_hi = l_hi.cwiseMax(bin_hi[b]);
        l_count += bin_count[b];
      }
      for (int b = split; b < kBins; ++b) {
        r_lo = r_lo.cwiseMin(bin_lo[b]);
        r_hi = r_hi.cwiseMax(bin_hi[b]);
        r_count += bin_count[b];
      }
      if (l_count == 0 || r_count == 0) continue;
      const double cost = area(l_lo, l_hi) * l_count + area(r_lo, r_hi) * r_count;
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_split = centre_lo[axis] + span * split / kBins;
      }
    }
  }
  int middle = (begin + end) / 2;
  if (best_axis >= 0) {
    const auto it = std::partition(order.begin() + begin, order.begin() + end, [&](int i) {
      return 0.5 * (lo[i][best_axis] + hi[i][best_axis]) < best_split;
    });
    middle = int(it - order.begin());
  }
  if (middle == begin || middle == end) middle = (begin + end) / 2;  // all centres coincide
  build(order, lo, hi, begin, middle);
  nodes_[index].first = int(nodes_.size());
  nodes_[index].count = 0;
  build(order, lo, hi, middle, end);
}

double RayCaster::intersectOther(int g, const Eigen::Vector3d& origin,
                                 const Eigen::Vector3d& direction) const {
  if (model_->geom_type[g] == mjGEOM_MESH) {
    return mj_rayMesh(model_, data_, g, origin.data(), direction.data());
  }
  return mju_rayGeom(data_->geom_xpos + 3 * g, data_->geom_xmat + 9 * g, model_->geom_size + 3 * g,
                     origin.data(), direction.data(), model_->geom_type[g]);
}

std::optional<RayCaster::Hit> RayCaster::cast(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& direction) const {
  Hit best;
  castAlwaysTested(origin, direction, best);
  if (!nodes_.empty()) {
    const Eigen::Vector3d inverse = direction.cwiseInverse();
    Pending stack[64];
    int top = 0;
    auto limit = [&best] { return best.distance < 0 ? kInfinity : best.distance; };
    const double root = slabEntry(nodes_[0].lo, nodes_[0].hi, origin, inverse, limit());
    if (root <= limit()) stack[top++] = {0, root};
    while (top > 0) {
      const Pending pending = stack[--top];
      if (pending.entry > limit()) continue;  // something nearer was found meanwhile
      const Node& node = nodes_[pending.node];
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          const Box& box = boxes_[fragment_box_[i]];
          best.consider(intersectSolid(box, origin, direction), box.geom);
        }
        continue;
      }
      // Visit the nearer child first: push it last.
      const int left = pending.node + 1;
      const int right = node.first;
      const double bound = limit();
      const double dl = slabEntry(nodes_[left].lo, nodes_[left].hi, origin, inverse, bound);
      const double dr = slabEntry(nodes_[right].lo, nodes_[right].hi, origin, inverse, bound);
      if (dl <= dr) {
        if (dr <= bound) stack[top++] = {right, dr};
        if (dl <= bound) stack[top++] = {left, dl};
      } else {
        if (dl <= bound) stack[top++] = {left, dl};
        if (dr <= bound) stack[top++] = {right, dr};
      }
    }
  }
  if (best.distance < 0) return std::nullopt;
  return best;
}

}  // namespace isg::sim
