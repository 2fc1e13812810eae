#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace isg::recordings {

// A recording's fixed frames (its /tf_static): a tree of parent → child transforms, asked for the
// transform between any two frames on it, by the path through their common ancestor.
class StaticFrames {
 public:
  // A later transform for the same child replaces the earlier one, as tf2 does.
  void add(const std::string& parent, const std::string& child,
           const Eigen::Isometry3d& parent_T_child);
  // a_T_b: frame b's pose in frame a; identity when a == b; nullopt when no path joins them.
  std::optional<Eigen::Isometry3d> transform(const std::string& a, const std::string& b) const;
  bool empty() const { return edges_.empty(); }
  // The edge above `child`: its parent frame and parent_T_child; nullopt at a root.
  std::optional<std::pair<std::string, Eigen::Isometry3d>> parent(const std::string& child) const;

 private:
  struct Edge {
    std::string parent, child;
    Eigen::Isometry3d parent_T_child;
  };
  // root_T_frame along the parents of `frame`, with the frames passed through (frame first).
  std::vector<std::pair<std::string, Eigen::Isometry3d>> chainToRoot(
      const std::string& frame) const;
  std::vector<Edge> edges_;
};

}  // namespace isg::recordings
