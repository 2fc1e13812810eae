#include "sim/robot_model.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "worlds/mjcf_generator.hpp"

namespace isg::sim {

namespace {

constexpr double kHipX = 0.30, kHipY = 0.055, kLegOffset = 0.11, kThigh = 0.32, kShin = 0.32;
constexpr const char* kLegs[] = {"FL", "FR", "RL", "RR"};
// Standing pose: the leg's hip and knee angles that put the feet 0.46 m below the hips.
constexpr double kHipStand = 0.75, kKneeStand = -1.5;

}  // namespace

RobotBox robotBodyBox() { return {{0.0, 0.0, 0.0}, {0.55, 0.25, 0.09}}; }

std::string robotMjcf(const Eigen::Isometry3d& R_T_L) {
  const int group = worlds::kRobotGroup;
  char buffer[4096];
  std::string out = "    <!-- the robot: a mocap body moved by the scripted trajectory -->\n";
  const RobotBox box = robotBodyBox();
  const Eigen::Vector3d l = R_T_L.translation();
  const Eigen::Quaterniond q(R_T_L.linear());
  std::snprintf(buffer, sizeof buffer,
                "    <body name=\"robot\" mocap=\"true\" pos=\"0 0 0.46\">\n"
                "      <geom name=\"robot/body\" type=\"box\" size=\"%g %g %g\" group=\"%d\" "
                "contype=\"0\" conaffinity=\"0\" rgba=\".95 .78 .1 1\"/>\n"
                "      <geom name=\"robot/mast\" type=\"cylinder\" fromto=\"%g %g %g %g %g %g\" "
                "size=\"0.02\" group=\"%d\" contype=\"0\" conaffinity=\"0\" rgba=\".2 .2 .2 1\"/>\n"
                "      <body name=\"robot/lidar\" pos=\"%g %g %g\" quat=\"%g %g %g %g\">\n"
                "        <geom name=\"robot/vlp16\" type=\"cylinder\" size=\"0.052 0.036\" "
                "group=\"%d\" contype=\"0\" conaffinity=\"0\" rgba=\".15 .15 .15 1\"/>\n"
                "      </body>\n",
                box.half.x(), box.half.y(), box.half.z(), group, l.x(), l.y(), box.half.z(), l.x(),
                l.y(), l.z() - 0.036, group, l.x(), l.y(), l.z(), q.w(), q.x(), q.y(), q.z(),
                group);
  out += buffer;
  for (int i = 0; i < 4; ++i) {
    const double x = i < 2 ? kHipX : -kHipX;
    const double side = i % 2 == 0 ? 1.0 : -1.0;
    std::snprintf(buffer, sizeof buffer,
                  "      <body name=\"robot/%s_hip\" pos=\"%g %g 0\">\n"
                  "        <joint name=\"robot/%s_hip\" type=\"hinge\" axis=\"0 1 0\"/>\n"
                  "        <geom type=\"capsule\" fromto=\"0 %g 0 0 %g %g\" size=\"0.04\" "
                  "group=\"%d\" contype=\"0\" conaffinity=\"0\" rgba=\".2 .2 .2 1\"/>\n"
                  "        <body name=\"robot/%s_knee\" pos=\"0 %g %g\">\n"
                  "          <joint name=\"robot/%s_knee\" type=\"hinge\" axis=\"0 1 0\"/>\n"
                  "          <geom type=\"capsule\" fromto=\"0 0 0 0 0 %g\" size=\"0.028\" "
                  "group=\"%d\" contype=\"0\" conaffinity=\"0\" rgba=\".95 .78 .1 1\"/>\n"
                  "        </body>\n"
                  "      </body>\n",
                  kLegs[i], x, side * kHipY, kLegs[i], side * kLegOffset, side * kLegOffset,
                  -kThigh, group, kLegs[i], side * kLegOffset, -kThigh, kLegs[i], -kShin, group);
    out += buffer;
  }
  out += "    </body>\n";
  return out;
}

void poseRobot(const mjModel& m, mjData& d, const Eigen::Isometry3d& B_T_R, double gait_phase,
               double sway_weight) {
  const int body = mj_name2id(&m, mjOBJ_BODY, "robot");
  if (body < 0) {  // a world without the robot (a handheld carrier): the building's kinematics
    mj_kinematics(&m, &d);
    return;
  }
  const int mocap = m.body_mocapid[body];
  const Eigen::Vector3d p = B_T_R.translation();
  const Eigen::Quaterniond q(B_T_R.linear());
  d.mocap_pos[3 * mocap + 0] = p.x();
  d.mocap_pos[3 * mocap + 1] = p.y();
  d.mocap_pos[3 * mocap + 2] = p.z();
  d.mocap_quat[4 * mocap + 0] = q.w();
  d.mocap_quat[4 * mocap + 1] = q.x();
  d.mocap_quat[4 * mocap + 2] = q.y();
  d.mocap_quat[4 * mocap + 3] = q.z();
  for (int i = 0; i < 4; ++i) {
    // Trot: diagonal legs (FL + RR, FR + RL) swing together, half a cycle apart.
    const double phase = gait_phase + ((i == 0 || i == 3) ? 0.0 : std::numbers::pi);
    const double swing = sway_weight * std::sin(phase);
    const double lift = sway_weight * std::max(0.0, std::sin(phase));
    const std::string leg = kLegs[i];
    const int hip = mj_name2id(&m, mjOBJ_JOINT, ("robot/" + leg + "_hip").c_str());
    const int knee = mj_name2id(&m, mjOBJ_JOINT, ("robot/" + leg + "_knee").c_str());
    d.qpos[m.jnt_qposadr[hip]] = kHipStand + 0.3 * swing;
    d.qpos[m.jnt_qposadr[knee]] = kKneeStand - 0.5 * lift;
  }
  mj_kinematics(&m, &d);
}

}  // namespace isg::sim
