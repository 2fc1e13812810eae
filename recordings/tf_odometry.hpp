#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "formats/ros_time.hpp"
#include "recordings/static_frames.hpp"

namespace isg::recordings {

// Odometry that a recording gives only as transforms on /tf (a Spot's odom → body, a navigation
// stack's odom → base_footprint → base_link) instead of nav_msgs/Odometry: the chain of frames
// from the odometry's fixed frame down to the robot's base, each link moving (a time series on
// /tf) or fixed (/tf_static). docs/formats.md, "Importing recordings".

// Which frame hangs from which on /tf. Learnt from the whole topic first, so that only the
// chain's transforms are kept afterwards (a robot's /tf also moves every joint it has). A link
// whose transform never changes over the topic is fixed: ROS 1's first tf had no /tf_static, and
// its static_transform_publisher repeats a mount on /tf.
class MovingFrameTree {
 public:
  // The parent `child` already has when that is not `parent` (a frame has one parent in tf),
  // else nullopt (recorded).
  std::optional<std::string> add(const std::string& parent, const std::string& child,
                                 const Eigen::Isometry3d& parent_T_child);
  // When parent → child would close a cycle through /tf's links and `fixed`'s: the cycle, top
  // down (StaticFrames::cycleIfAdded).
  std::optional<std::string> cycleIfAdded(const std::string& parent, const std::string& child,
                                          const StaticFrames& fixed) const;
  struct FixedLink {
    std::string parent, child;
    Eigen::Isometry3d parent_T_child;
  };
  // The links whose every transform was the first one (to 1e-9).
  std::vector<FixedLink> unchanging() const;

  struct Above {
    std::string frame;  // a frame above the one asked about
    bool moving;        // the link up to it from the frame below changes on /tf
    Eigen::Isometry3d fixed_parent_T_child = Eigen::Isometry3d::Identity();  // when not moving
  };
  // The frames above `frame` through /tf's links and /tf_static's, nearest first. A frame with a
  // parent on both hangs from its /tf one (where /tf says it is now).
  std::vector<Above> above(const std::string& frame, const StaticFrames& fixed) const;

 private:
  struct Link {
    std::string parent;
    Eigen::Isometry3d first;
    bool changes = false;
  };
  std::map<std::string, Link> link_of_;  // by child
};

// A frame named as an odometry frame: its last '/'-part is "odom" or begins with it
// ("odom_combined", "odometry", "robot1/odom").
bool namedLikeOdometry(const std::string& frame);

// The pose of `base` in `top` over time, from the transforms of the chain between them.
class TfOdometry {
 public:
  // `above` is MovingFrameTree::above(base, …); `top` must be on it with a moving link at or
  // below it (std::invalid_argument otherwise, saying which).
  TfOdometry(const std::string& top, const std::string& base,
             const std::vector<MovingFrameTree::Above>& above);

  // One transform of /tf, kept when it moves a link of the chain. A stamp before the link's
  // previous one is std::invalid_argument; a repeated stamp is dropped (counted in repeated()).
  void offer(const std::string& parent, const std::string& child, formats::RosTime stamp,
             const Eigen::Isometry3d& parent_T_child);

  struct Pose {
    formats::RosTime stamp;
    Eigen::Isometry3d top_T_base;
  };
  // top_T_base at each stamp of the moving link nearest the base; other moving links are
  // interpolated there (positions linearly, rotations by slerp), and a stamp outside one's span
  // is left out.
  std::vector<Pose> poses() const;
  // "odom → base_footprint (moving) → base_link (fixed)"
  std::string describe() const;
  std::uint64_t repeated() const { return repeated_; }

 private:
  struct Link {
    std::string parent, child;
    bool moving;
    Eigen::Isometry3d fixed_parent_T_child;
    std::vector<std::pair<formats::RosTime, Eigen::Isometry3d>> samples;  // when moving
  };
  std::vector<Link> links_;  // from the top down to the base
  std::uint64_t repeated_ = 0;
};

}  // namespace isg::recordings
