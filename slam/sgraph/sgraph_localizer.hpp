#pragma once

#include "slam/localizer.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// The S-Graph behind the Localizer interface: what the testbed's loop and `isg slam` feed. It
// localizes in its own map frame M only; the plan comes with the iS-Graph (isgraph_localizer.hpp).
class SGraphLocalizer : public Localizer {
 public:
  SGraphLocalizer(const Eigen::Isometry3d& R_T_L, const SGraphOptions& options = {})
      : graph_(R_T_L, options) {}

  std::string name() const override { return "s-graph"; }
  void pushOdometry(const sensors::Odometry& odometry) override { graph_.addOdometry(odometry); }
  void pushScan(const sensors::Scan& scan) override { graph_.addScan(scan); }
  void pushImu(const sensors::ImuSample& sample) override { graph_.addImu(sample); }
  void setImuMount(const Eigen::Isometry3d& R_T_I) { graph_.setImuMount(R_T_I); }
  bool wantsScan(double stamp) const override { return graph_.wouldKeyframe(stamp); }
  std::optional<sensors::Odometry> poseInMap() const override { return graph_.latestPose(); }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return std::nullopt; }
  nlohmann::json graph() const override { return graph_.toJson(); }
  std::optional<MapDiagnostics> mapDiagnostics() const override { return graph_.diagnostics(); }
  sensors::StageTimes stageTimes() const override { return graph_.stageTimes(); }

  const SGraph& sgraph() const { return graph_; }

 private:
  SGraph graph_;
};

}  // namespace isg::slam
