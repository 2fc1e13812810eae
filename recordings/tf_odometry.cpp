#include "recordings/tf_odometry.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

#include "common/pose_interpolation.hpp"

namespace isg::recordings {

namespace {

// Seconds from `reference` to `t`, exact to the nanosecond over a recording's length (a double
// of the whole epoch time would keep only ~0.1 µs).
double secondsSince(formats::RosTime t, formats::RosTime reference) {
  return double(std::int64_t(t.sec) - std::int64_t(reference.sec)) +
         1e-9 * double(std::int64_t(t.nsec) - std::int64_t(reference.nsec));
}

bool sameStamp(formats::RosTime a, formats::RosTime b) {
  return a.sec == b.sec && a.nsec == b.nsec;
}

}  // namespace

std::optional<std::string> MovingFrameTree::add(const std::string& parent, const std::string& child,
                                                const Eigen::Isometry3d& parent_T_child) {
  const auto [it, inserted] = link_of_.emplace(child, Link{parent, parent_T_child});
  if (inserted) return std::nullopt;
  if (it->second.parent != parent) return it->second.parent;
  constexpr double kSame = 1e-9;
  if ((it->second.first.matrix() - parent_T_child.matrix()).cwiseAbs().maxCoeff() > kSame) {
    it->second.changes = true;
  }
  return std::nullopt;
}

std::optional<std::string> MovingFrameTree::cycleIfAdded(const std::string& parent,
                                                         const std::string& child,
                                                         const StaticFrames& fixed) const {
  // A frame with a parent on both hangs from its /tf one, as above() reads the tree.
  return cycleThrough(parent, child, [&](const std::string& frame) -> std::optional<std::string> {
    if (const auto on_tf = link_of_.find(frame); on_tf != link_of_.end()) {
      return on_tf->second.parent;
    }
    if (const auto link = fixed.parent(frame)) return link->first;
    return std::nullopt;
  });
}

std::vector<MovingFrameTree::FixedLink> MovingFrameTree::unchanging() const {
  std::vector<FixedLink> out;
  for (const auto& [child, link] : link_of_) {
    if (!link.changes) out.push_back({link.parent, child, link.first});
  }
  return out;
}

std::vector<MovingFrameTree::Above> MovingFrameTree::above(const std::string& frame,
                                                           const StaticFrames& fixed) const {
  std::vector<Above> chain;
  std::set<std::string> seen = {frame};
  std::string current = frame;
  for (;;) {
    Above next;
    if (const auto on_tf = link_of_.find(current); on_tf != link_of_.end()) {
      next = {on_tf->second.parent, on_tf->second.changes, on_tf->second.first};
    } else if (const auto link = fixed.parent(current)) {
      next = {link->first, false, link->second};
    } else {
      break;
    }
    if (!seen.insert(next.frame).second) break;  // a cycle: tf would refuse it too
    current = next.frame;
    chain.push_back(std::move(next));
  }
  return chain;
}

bool namedLikeOdometry(const std::string& frame) {
  const std::size_t slash = frame.rfind('/');
  std::string part = slash == std::string::npos ? frame : frame.substr(slash + 1);
  for (char& c : part) c = char(std::tolower(static_cast<unsigned char>(c)));
  return part.starts_with("odom");
}

TfOdometry::TfOdometry(const std::string& top, const std::string& base,
                       const std::vector<MovingFrameTree::Above>& above) {
  std::string below = base;
  bool reached = false;
  for (const auto& link : above) {
    links_.push_back({link.frame, below, link.moving, link.fixed_parent_T_child, {}});
    below = link.frame;
    if (link.frame == top) {
      reached = true;
      break;
    }
  }
  if (!reached) {
    throw std::invalid_argument("the frame \"" + top + "\" is not above \"" + base + "\"");
  }
  std::reverse(links_.begin(), links_.end());
  if (std::none_of(links_.begin(), links_.end(), [](const Link& l) { return l.moving; })) {
    throw std::invalid_argument("nothing on /tf moves \"" + base + "\" in \"" + top +
                                "\": the frames join by /tf_static alone");
  }
}

void TfOdometry::offer(const std::string& parent, const std::string& child, formats::RosTime stamp,
                       const Eigen::Isometry3d& parent_T_child) {
  for (auto& link : links_) {
    if (!link.moving || link.child != child || link.parent != parent) continue;
    if (!link.samples.empty()) {
      if (sameStamp(link.samples.back().first, stamp)) {
        ++repeated_;
        return;
      }
      if (stamp < link.samples.back().first) {
        throw std::invalid_argument("its transform " + parent + " → " + child +
                                    " is stamped before the previous one");
      }
    }
    link.samples.emplace_back(stamp, parent_T_child);
    return;
  }
}

std::vector<TfOdometry::Pose> TfOdometry::poses() const {
  // The stamps come from the moving link nearest the base (the odometry's own transform, as a
  // rule); the others are interpolated there.
  const auto driving =
      std::find_if(links_.rbegin(), links_.rend(), [](const Link& l) { return l.moving; });
  if (driving->samples.empty()) return {};
  const formats::RosTime reference = driving->samples.front().first;
  std::vector<common::Trajectory> series(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (!links_[i].moving || &links_[i] == &*driving) continue;
    for (const auto& [stamp, T] : links_[i].samples) {
      series[i].push_back({secondsSince(stamp, reference), T});
    }
  }
  std::vector<Pose> poses;
  for (const auto& [stamp, driving_T] : driving->samples) {
    const double t = secondsSince(stamp, reference);
    Eigen::Isometry3d top_T_base = Eigen::Isometry3d::Identity();
    bool covered = true;
    for (std::size_t i = 0; i < links_.size() && covered; ++i) {
      const Link& link = links_[i];
      if (!link.moving) {
        top_T_base = top_T_base * link.fixed_parent_T_child;
      } else if (&link == &*driving) {
        top_T_base = top_T_base * driving_T;
      } else if (const auto T = common::interpolatePose(series[i], t)) {
        top_T_base = top_T_base * *T;
      } else {
        covered = false;
      }
    }
    if (covered) poses.push_back({stamp, top_T_base});
  }
  return poses;
}

std::string TfOdometry::describe() const {
  std::string text = links_.front().parent;
  for (const auto& link : links_) {
    text += " → " + link.child + (link.moving ? " (moving)" : " (fixed)");
  }
  return text;
}

}  // namespace isg::recordings
