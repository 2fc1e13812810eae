#pragma once

#include <optional>
#include <string>

#include "common/pose_track.hpp"
#include "common/tum.hpp"
#include "eval/alignment.hpp"
#include "eval/association.hpp"

namespace isg::eval {

// Statistics of an error series, as evo reports them (std is the population std).
struct Statistics {
  int count = 0;
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0, sse = 0;
};
Statistics statistics(std::vector<double> values);

enum class Alignment { kNone, kSE3, kSim3 };

struct ErrorOptions {
  Alignment align = Alignment::kNone;  // global localization is judged in B: none by default
  bool project_xy = false;             // zero z, keep yaw only (the paper's 2D APE)
  double max_diff = 0.01;              // association window, seconds (evo's --t_max_diff)
  int rpe_delta = 1;                   // RPE: pose pairs this many associated poses apart
};

struct ErrorResult {
  Association association;
  std::optional<Similarity> alignment;  // applied to the estimate, when asked for
  std::vector<double> translation;      // per associated pose (APE) or pair (RPE), metres
  std::vector<double> rotation_deg;     // angle of R_ref⁻¹ R_est, degrees
  Statistics translation_stats;
  Statistics rotation_stats;
};

// Absolute pose error, evo's order of steps: associate, align (Umeyama on the associated
// positions), then project, then compare. Throws std::invalid_argument when nothing associates
// (or too little to align).
ErrorResult absolutePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options);
// The same, with the estimate's poses placed by `placement` first (B_T_M · pose): the odometry
// judged from the true start without a placed copy of hours of it.
ErrorResult absolutePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options,
                              const std::optional<Eigen::Isometry3d>& placement);

// Relative pose error over `rpe_delta` associated poses: E = (Rᵢ⁻¹Rⱼ)⁻¹(Eᵢ⁻¹Eⱼ).
ErrorResult relativePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options);

// The pose with z = 0 and only the rotation about z kept.
Eigen::Isometry3d projectXY(const Eigen::Isometry3d& pose);

const char* toString(Alignment alignment);

}  // namespace isg::eval
