#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <vector>

#include "sensors/messages.hpp"
#include "sensors/stage_times.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::slam {

// A localization method: sensor data in, poses out. The testbed's loop and `isg slam` feed any
// implementation the same way, in time order; nothing here knows about the simulator.
class Localizer {
 public:
  virtual ~Localizer() = default;

  virtual std::string name() const = 0;
  virtual void pushOdometry(const sensors::Odometry& odometry) = 0;
  virtual void pushScan(const sensors::Scan& scan) = 0;
  // The IMU, up to the end of the next scan's turn before that scan. Methods that do not read
  // it keep the default.
  virtual void pushImu(const sensors::ImuSample& /*sample*/) {}
  // Whether pushScan would read the scan stamped `stamp`, given the odometry pushed so far (up to
  // the end of that scan's turn). When it says no, a loop may leave the scan unmade and not push
  // it at all: the method must then end up exactly as if it had been pushed. Methods that read
  // every scan keep the default.
  virtual bool wantsScan(double /*stamp*/) const { return true; }

  // The latest estimate of the base in the map frame M, once there is one.
  virtual std::optional<sensors::Odometry> poseInMap() const = 0;
  // B_T_M, once the method knows where its map lies in the plan frame B.
  virtual std::optional<Eigen::Isometry3d> mapInPlan() const = 0;
  // Once mapInPlan() has a value: whether the plan confirms the latest pose — what placed it is
  // still tied to the plan's walls here — or only the method's map and odometry carry it (the
  // run's "tracking" state, docs/evaluation.md "An estimate for every scan"). Methods that do
  // not tell keep the default: placed is confirmed.
  virtual bool planConfirms() const { return true; }
  // The method's graph (or state) for the run folder's sgraph.json.
  virtual nlohmann::json graph() const = 0;

  // For methods that search for their place in the plan: the search's status now, in words for
  // the summary and metrics.json's `matching_status` (the matcher's status, "matched", or AMCL's
  // particles and heaviest cluster), and every change of the matcher's status, typed
  // (MatchStatus). Methods that do not search have none.
  virtual std::optional<std::string> searchStatus() const { return std::nullopt; }
  virtual std::vector<StatusChange> statusChanges() const { return {}; }
  // For methods that build a map: its keyframes, planes, rooms and timings.
  virtual std::optional<MapDiagnostics> mapDiagnostics() const { return std::nullopt; }
  // Seconds spent in each of the method's stages so far (deskew, extraction, matching, ...), for
  // the run's stage timing. Methods that do not report stages have none: their time shows as the
  // localizer's own.
  virtual sensors::StageTimes stageTimes() const { return {}; }
};

// The baseline: odometry alone, its map frame placed in the plan by a pose given from outside
// (the evaluation's "dead reckoning started at the true pose").
class DeadReckoning : public Localizer {
 public:
  explicit DeadReckoning(std::optional<Eigen::Isometry3d> B_T_M = std::nullopt) : B_T_M_(B_T_M) {}

  std::string name() const override { return "odometry"; }
  void pushOdometry(const sensors::Odometry& odometry) override { latest_ = odometry; }
  void pushScan(const sensors::Scan&) override {}
  bool wantsScan(double) const override { return false; }
  std::optional<sensors::Odometry> poseInMap() const override { return latest_; }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return B_T_M_; }
  nlohmann::json graph() const override { return {{"method", name()}}; }

 private:
  std::optional<Eigen::Isometry3d> B_T_M_;
  std::optional<sensors::Odometry> latest_;
};

}  // namespace isg::slam
