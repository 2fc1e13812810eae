#include "recordings/static_frames.hpp"

namespace isg::recordings {

void StaticFrames::add(const std::string& parent, const std::string& child,
                       const Eigen::Isometry3d& parent_T_child) {
  for (auto& edge : edges_) {
    if (edge.child == child) {
      edge = {parent, child, parent_T_child};
      return;
    }
  }
  edges_.push_back({parent, child, parent_T_child});
}

std::optional<std::pair<std::string, Eigen::Isometry3d>> StaticFrames::parent(
    const std::string& child) const {
  for (const auto& edge : edges_) {
    if (edge.child == child) return std::make_pair(edge.parent, edge.parent_T_child);
  }
  return std::nullopt;
}

std::optional<std::string> StaticFrames::cycleIfAdded(const std::string& parent,
                                                      const std::string& child) const {
  return cycleThrough(parent, child, [&](const std::string& frame) -> std::optional<std::string> {
    if (const auto up = this->parent(frame)) return up->first;
    return std::nullopt;
  });
}

std::vector<std::pair<std::string, Eigen::Isometry3d>> StaticFrames::chainToRoot(
    const std::string& frame) const {
  // Each element: a frame on the way up and that frame's T of `frame` (ancestor_T_frame).
  std::vector<std::pair<std::string, Eigen::Isometry3d>> chain = {
      {frame, Eigen::Isometry3d::Identity()}};
  std::string current = frame;
  Eigen::Isometry3d ancestor_T_frame = Eigen::Isometry3d::Identity();
  // At most one parent per child, so the walk ends unless the tree has a cycle: bounded by the
  // number of edges.
  for (std::size_t step = 0; step < edges_.size(); ++step) {
    const Edge* up = nullptr;
    for (const auto& edge : edges_) {
      if (edge.child == current) up = &edge;
    }
    if (!up) break;
    ancestor_T_frame = up->parent_T_child * ancestor_T_frame;
    current = up->parent;
    chain.push_back({current, ancestor_T_frame});
  }
  return chain;
}

std::optional<Eigen::Isometry3d> StaticFrames::transform(const std::string& a,
                                                         const std::string& b) const {
  if (a == b) return Eigen::Isometry3d::Identity();
  const auto from_a = chainToRoot(a);
  const auto from_b = chainToRoot(b);
  for (const auto& [ancestor, ancestor_T_a] : from_a) {
    for (const auto& [other, ancestor_T_b] : from_b) {
      if (other == ancestor) return ancestor_T_a.inverse() * ancestor_T_b;
    }
  }
  return std::nullopt;
}

}  // namespace isg::recordings
