#include "cli/cmd_render.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "bim/plan_geometry.hpp"
#include "common/atomic_folder.hpp"
#include "sim/renderer.hpp"
#include "sim/robot_model.hpp"
#include "sim/simulation.hpp"

namespace isg::cli {

RenderCommand::RenderCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("render", "Draw the world and the walking robot as PNG pictures");
  app_->footer(
      "Writes DIR/top.png (the building from above in perspective, ceilings hidden), DIR/plan.png "
      "(straight down and orthographic to the eye, so walls show as footprints and door openings "
      "as gaps, with the robot's whole route drawn in red) and DIR/chase.png (behind the robot) "
      "at robot time T on its route. Renders on the CPU through EGL (Mesa, surfaceless "
      "platform): no display and no GPU needed.\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->required();
  app_->add_option("-o,--output", output_, "folder for the pictures (created if missing)")
      ->required();
  app_->add_option("--time", time_, "robot time in seconds (default: a quarter of the route)")
      ->check(nonNegativeNumber());
  app_->add_option("--width", width_, "picture width in pixels")
      ->check(CLI::Range(16, 1920))
      ->capture_default_str();
  app_->add_option("--height", height_, "picture height in pixels")
      ->check(CLI::Range(16, 1080))
      ->capture_default_str();
}

int RenderCommand::run() {
  namespace fs = std::filesystem;
  const fs::path dir(output_);
  // The folder may hold other files; of the pictures, only earlier ones of ours are replaced.
  common::checkOutputPath(output_, {common::OutputKind::kPictures, {inputFile(input_)}});
  for (const char* name : {"top.png", "plan.png", "chase.png"}) {
    common::checkOutputPath((dir / name).string(),
                            {common::OutputKind::kPng, {inputFile(input_)}, true, false});
  }
  // The folder is made with the first picture (and removed again if that fails); whether it can
  // be is checked above with each picture's path.
  const bim::Scenario scenario = loadInput(input_, "render");
  sim::Simulation simulation(scenario);
  const double t =
      time_ < 0 ? 0.25 * simulation.duration() : std::min(time_, simulation.duration());
  const auto& trajectory = simulation.baseMotion();
  const Eigen::Isometry3d B_T_R = trajectory.pose(t);
  auto& world = simulation.world();
  sim::poseRobot(world.model(), world.data(), B_T_R, trajectory.gaitPhase(t),
                 trajectory.swayWeight(t));
  sim::Renderer renderer(world.model(), width_, height_);
  const std::string top = (dir / "top.png").string();
  const std::string plan = (dir / "plan.png").string();
  const std::string chase = (dir / "chase.png").string();
  sim::writePng(top, renderer.topDown(world.data()));
  // The plan view frames the robot's level; the route is drawn 5 cm above its floor.
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18), hi = -lo;
  for (const auto& wall : bim::computeLevelGeometry(level).walls) {
    for (const auto& p : wall.footprint()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  std::vector<Eigen::Vector3d> route;
  for (double s = 0.0; s <= simulation.duration(); s += 0.25) {
    const Eigen::Vector3d p = trajectory.pose(s).translation();
    route.emplace_back(p.x(), p.y(), level.elevation + 0.05);
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  sim::writePng(plan, renderer.planView(world.data(), lo, hi, route));
  sim::writePng(chase, renderer.chase(world.data(), B_T_R));
  std::printf("isg render: wrote %s, %s and %s at t = %.1f s (robot at %.2f, %.2f; %s)\n",
              top.c_str(), plan.c_str(), chase.c_str(), t, B_T_R.translation().x(),
              B_T_R.translation().y(), renderer.glRenderer().c_str());
  return kExitOk;
}

}  // namespace isg::cli
