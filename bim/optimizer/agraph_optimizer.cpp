#include "bim/optimizer/agraph_optimizer.hpp"

#include "bim/optimizer/agraph_factors.hpp"

namespace isg::bim {

AGraphState::AGraphState(const AGraph& graph)
    : graph_(&graph),
      plane_manifold_(std::make_unique<PlaneManifold>()),
      doorway_manifold_(std::make_unique<ceres::SubsetManifold>(3, std::vector<int>{2})) {
  for (const auto& s : graph.surfaces) planes.push_back(toVector(s.plane));
  for (const auto& w : graph.walls) walls.push_back(w.centre);
  for (const auto& r : graph.rooms) rooms.push_back(r.centre);
  for (const auto& d : graph.doorways) doorways.push_back(d.position);
}

void AGraphState::addToProblem(ceres::Problem& problem, const AGraphSigmas& sigmas,
                               bool plane_priors) {
  // The manifolds are owned here, not by the problem.
  for (std::size_t i = 0; i < planes.size(); ++i) {
    problem.AddParameterBlock(planes[i].data(), 4, plane_manifold_.get());
    if (plane_priors) {
      problem.AddResidualBlock(PlanePriorFactor::create(toVector(graph_->surfaces[i].plane),
                                                        sigmas.plane_angle, sigmas.plane_distance),
                               nullptr, planes[i].data());
    }
  }
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const WallNode& w = graph_->walls[i];
    problem.AddResidualBlock(WallFactor::create(w.anchor, sigmas.wall), nullptr, walls[i].data(),
                             planes[w.left_surface].data(), planes[w.right_surface].data());
  }
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    const RoomNode& r = graph_->rooms[i];
    problem.AddParameterBlock(rooms[i].data(), 2);
    if (r.kind == RoomKind::kFourWall) {
      problem.AddResidualBlock(FourWallRoomFactor::create(sigmas.room), nullptr, rooms[i].data(),
                               planes[r.pairs[0][0]].data(), planes[r.pairs[0][1]].data(),
                               planes[r.pairs[1][0]].data(), planes[r.pairs[1][1]].data());
    } else if (r.kind == RoomKind::kTwoWall) {
      problem.AddResidualBlock(TwoWallRoomFactor::create(r.axis_point, sigmas.room), nullptr,
                               rooms[i].data(), planes[r.pairs[0][0]].data(),
                               planes[r.pairs[0][1]].data());
    }
  }
  for (std::size_t i = 0; i < doorways.size(); ++i) {
    const DoorwayNode& d = graph_->doorways[i];
    if (d.rooms.empty()) continue;
    problem.AddParameterBlock(doorways[i].data(), 3, doorway_manifold_.get());
    // The door as seen from each room: its offset from the room's centre in the plan.
    auto from = [&](int room) -> Eigen::Vector2d {
      return d.position.head<2>() - graph_->rooms[room].centre;
    };
    if (d.rooms.size() == 2) {
      problem.AddResidualBlock(
          DoorwayFactor::create(from(d.rooms[0]), from(d.rooms[1]), sigmas.doorway), nullptr,
          rooms[d.rooms[0]].data(), rooms[d.rooms[1]].data(), doorways[i].data());
    } else {
      problem.AddResidualBlock(OutsideDoorwayFactor::create(from(d.rooms[0]), sigmas.doorway),
                               nullptr, rooms[d.rooms[0]].data(), doorways[i].data());
    }
  }
}

double AGraphState::optimize(const AGraphSigmas& sigmas, bool plane_priors, bool fix_planes) {
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  addToProblem(problem, sigmas, plane_priors);
  if (fix_planes) {
    for (auto& p : planes) problem.SetParameterBlockConstant(p.data());
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.final_cost;
}

}  // namespace isg::bim
