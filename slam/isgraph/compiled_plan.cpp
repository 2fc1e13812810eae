#include "slam/isgraph/compiled_plan.hpp"

namespace isg::slam {

CompiledPlan::CompiledPlan(const bim::AGraph& plan, const MatchingOptions& matching,
                           double outside_margin)
    : B_t_P_(plan.localOrigin()),
      plan_in_P_(plan.translated(-B_t_P_)),
      field_(plan_in_P_),
      matcher_(plan_in_P_, matching) {
  // The box of the plan's walls and the margin: a pose outside it is no pose in the building.
  const Eigen::AlignedBox2d walls = plan_in_P_.surfaceBounds();
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(outside_margin);
  building_ = Eigen::AlignedBox2d(walls.min() - margin, walls.max() + margin);
  if (plan_in_P_.floors.size() > 1) {
    level_matcher_ = std::make_unique<LevelMatcher>(plan_in_P_, matching);
    flights_ = flightFootprints(plan_in_P_);
  }
}

Eigen::Vector3d CompiledPlan::inB(const Eigen::Vector3d& P_T_M_x_y_yaw) const {
  return {P_T_M_x_y_yaw.x() + B_t_P_.x(), P_T_M_x_y_yaw.y() + B_t_P_.y(), P_T_M_x_y_yaw.z()};
}

Eigen::Vector3d CompiledPlan::inP(const Eigen::Vector3d& B_T_M_x_y_yaw) const {
  return {B_T_M_x_y_yaw.x() - B_t_P_.x(), B_T_M_x_y_yaw.y() - B_t_P_.y(), B_T_M_x_y_yaw.z()};
}

const GraphMatcher& CompiledPlan::matcherOf(int level) const {
  return level_matcher_ ? level_matcher_->matcher(level) : matcher_;
}

MatchResult CompiledPlan::match(const MatchInput& input, int* level, ThreadPool* pool) const {
  if (!level_matcher_) {
    *level = -1;
    return matcher_.match(input, pool);
  }
  LevelMatch match = level_matcher_->match(input, pool);
  *level = match.level;
  return std::move(match.result);
}

Verification CompiledPlan::verify(const MatchInput& input, const Eigen::Vector3d& P_T_M_x_y_yaw,
                                  int level) const {
  if (!level_matcher_) return matcher_.verify(input, P_T_M_x_y_yaw);
  return level_matcher_->verify(input, P_T_M_x_y_yaw, level);
}

Verification CompiledPlan::verifyOnBestLevel(const MatchInput& input,
                                             const Eigen::Vector3d& P_T_M_x_y_yaw,
                                             int* level) const {
  *level = -1;
  Verification answer = matcher_.verify(input, P_T_M_x_y_yaw);
  if (level_matcher_) {
    for (int l = 0; l < level_matcher_->levels(); ++l) {
      Verification on_level = level_matcher_->verify(input, P_T_M_x_y_yaw, l);
      if (*level < 0 || on_level.score > answer.score) answer = std::move(on_level), *level = l;
    }
  }
  return answer;
}

}  // namespace isg::slam
