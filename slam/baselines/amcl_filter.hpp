#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "slam/baselines/amcl_motion_model.hpp"
#include "slam/baselines/likelihood_field.hpp"
#include "slam/baselines/pose2.hpp"

namespace isg::slam {

// ROS AMCL's particle filter (Fox's KLD sampling, Thrun et al.'s augmented MCL), with nav2's
// defaults. docs/baselines.md says where each number comes from.
struct ParticleFilterOptions {
  int min_particles = 500;   // nav2 min_particles
  int max_particles = 2000;  // nav2 max_particles
  // KLD sampling: enough particles that the sampled belief is within kld_err of the true one
  // with probability kld_z, over histogram bins of 0.5 m × 0.5 m × 10°. AMCL passes pf_z (0.99)
  // as the normal quantile itself, not the quantile of 0.99 (2.33); so do we.
  double kld_err = 0.05;  // nav2 pf_err
  double kld_z = 0.99;    // nav2 pf_z
  double bin_size = 0.5;  // metres, AMCL's kd-tree cells
  double bin_angle = 10.0 * M_PI / 180.0;
  // Augmented MCL: short- and long-term averages of the measurement likelihood; when the short
  // one drops below the long one, that share of the resampled particles is drawn uniformly over
  // the free space. nav2 ships these at 0 (off); the ROS wiki suggests 0.001 and 0.1.
  double alpha_slow = 0.001;
  double alpha_fast = 0.1;
  // Likelihood field sensor model.
  double z_hit = 0.5;        // nav2 z_hit
  double z_rand = 0.5;       // nav2 z_rand
  double sigma_hit = 0.2;    // nav2 sigma_hit, metres
  double max_range = 100.0;  // laser_max_range: beams at or past it are skipped
  int max_beams = 60;        // nav2 max_beams
  OdometryMotionNoise motion;
};

struct Particle {
  Pose2 pose;
  double weight = 0.0;
};

// A set of particles in adjacent histogram bins: one hypothesis.
struct ParticleCluster {
  double weight = 0.0;  // share of the total weight
  int count = 0;
  Pose2 mean;                                            // weighted; yaw the circular mean
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // of x, y
  double yaw_variance = 0.0;                             // −2 ln R of the circular mean
};

class ParticleFilter {
 public:
  ParticleFilter(const LikelihoodField& map, const ParticleFilterOptions& options,
                 std::uint64_t seed);

  // max_particles particles drawn uniformly over the map's free space (global localization).
  void initUniform();
  // Moves every particle by the odometry's move from `from` to `to`, with the model's noise.
  void motionUpdate(const Pose2& from, const Pose2& to);
  // Weighs every particle by the likelihood field of the beams' end points (in the base frame);
  // updates the averages of augmented MCL.
  void sensorUpdate(const std::vector<Eigen::Vector2d>& endpoints);
  // KLD-sampling resampling with random injection; then the clusters.
  void resample();

  const std::vector<Particle>& particles() const { return particles_; }
  // Heaviest first.
  const std::vector<ParticleCluster>& clusters() const { return clusters_; }
  double wSlow() const { return w_slow_; }
  double wFast() const { return w_fast_; }
  // The measurement likelihood of one pose (the factor sensorUpdate multiplies a weight by).
  double likelihood(const Pose2& pose, const std::vector<Eigen::Vector2d>& endpoints) const;
  // AMCL's KLD bound: particles needed for k occupied bins.
  int kldLimit(int occupied_bins) const;

 private:
  Pose2 randomFreePose();
  void computeClusters();

  const LikelihoodField& map_;
  ParticleFilterOptions options_;
  std::mt19937_64 rng_;
  std::vector<Particle> particles_;
  std::vector<ParticleCluster> clusters_;
  double w_slow_ = 0.0, w_fast_ = 0.0;
};

}  // namespace isg::slam
