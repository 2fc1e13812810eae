#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace isg::recordings {

// The cycle a transform parent → child closes, given the parent of any frame (`parentOf`, nullopt
// at a root): "child → … → parent → child" read top-down, or nullopt when there is none.
template <typename ParentOf>
std::optional<std::string> cycleThrough(const std::string& parent, const std::string& child,
                                        const ParentOf& parentOf) {
  std::vector<std::string> up = {parent};  // parent, its parent, … (bounded: a cycle above stops)
  while (up.back() != child) {
    const std::optional<std::string> next = parentOf(up.back());
    if (!next || std::find(up.begin(), up.end(), *next) != up.end()) return std::nullopt;
    up.push_back(*next);
  }
  std::string text = child;
  for (auto frame = up.rbegin() + 1; frame != up.rend(); ++frame) text += " → " + *frame;
  return text + " → " + child;
}

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
  // The frames up from `parent` to `child` when a transform parent → child would close a cycle
  // (child hangs, through parent, from itself): "base_link → velodyne → base_link". tf's frames
  // form a tree, so such a transform is refused rather than ignored.
  std::optional<std::string> cycleIfAdded(const std::string& parent,
                                          const std::string& child) const;
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
