#include "bim/plan_transform.hpp"

#include "common/angles.hpp"

namespace isg::bim {

namespace {

double yawOf(const Eigen::Isometry2d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

// A pose [x, y, yaw] moved by T.
Eigen::Vector3d movedPose(const Eigen::Isometry2d& T, const Eigen::Vector3d& pose) {
  const Eigen::Vector2d xy = T * Eigen::Vector2d(pose.head<2>());
  return {xy.x(), xy.y(), common::wrapAngle(pose.z() + yawOf(T))};
}

}  // namespace

Eigen::Isometry2d planarMotion(const Eigen::Vector2d& translation, double yaw) {
  Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
  T.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  T.translation() = translation;
  return T;
}

Plan transformedPlan(const Plan& plan, const Eigen::Isometry2d& T) {
  Plan moved = plan;
  for (Level& level : moved.levels) {
    for (Wall& wall : level.walls) {
      wall.start = T * wall.start;
      wall.end = T * wall.end;
    }
    // A rotation keeps an outline counter-clockwise.
    for (Room& room : level.rooms) {
      for (Eigen::Vector2d& vertex : room.outline) vertex = T * vertex;
    }
    for (Stair& stair : level.stairs) {
      stair.start = T * stair.start;
      stair.end = T * stair.end;
    }
    for (Column& column : level.columns) {
      column.center = T * column.center;
      if (!column.round()) column.yaw = common::wrapAngle(column.yaw + yawOf(T));
    }
  }
  return moved;
}

Scenario transformedScenario(const Scenario& scenario, const Eigen::Isometry2d& T) {
  Scenario moved = scenario;
  moved.plan = transformedPlan(scenario.plan, T);
  RobotConfig& robot = moved.robot;
  if (robot.start_pose) robot.start_pose = movedPose(T, *robot.start_pose);
  for (Eigen::Vector2d& waypoint : robot.route.waypoints) waypoint = T * waypoint;
  for (Kidnap& kidnap : robot.kidnap) {
    if (kidnap.pose) kidnap.pose = movedPose(T, *kidnap.pose);
  }
  for (ExtraWall& wall : moved.as_built.extra_walls) {
    wall.start = T * wall.start;
    wall.end = T * wall.end;
  }
  for (Clutter& box : moved.as_built.clutter) {
    const Eigen::Vector2d xy = T * Eigen::Vector2d(box.center.head<2>());
    box.center.head<2>() = xy;
    box.yaw = common::wrapAngle(box.yaw + yawOf(T));
  }
  return moved;
}

}  // namespace isg::bim
