#include "slam/baselines/amcl_filter.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace isg::slam {

namespace {

using BinKey = std::array<int, 3>;

std::int64_t pack(const BinKey& k) {
  constexpr std::int64_t kOffset = 1 << 20;  // bins of ±1 million: ±500 km at 0.5 m
  return ((k[0] + kOffset) << 42) | ((k[1] + kOffset) << 21) | (k[2] + kOffset);
}

}  // namespace

ParticleFilter::ParticleFilter(const LikelihoodField& map, const ParticleFilterOptions& options,
                               std::uint64_t seed)
    : map_(map), options_(options), rng_(seed) {}

Pose2 ParticleFilter::randomFreePose() {
  const auto& cells = map_.freeCells();
  std::uniform_int_distribution<std::size_t> pick(0, cells.size() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d corner = map_.cellCorner(cells[pick(rng_)]);
  return {corner.x() + unit(rng_) * map_.resolution(), corner.y() + unit(rng_) * map_.resolution(),
          (2.0 * unit(rng_) - 1.0) * M_PI};
}

void ParticleFilter::initUniform() {
  particles_.assign(options_.max_particles, {});
  for (auto& p : particles_) p = {randomFreePose(), 1.0 / options_.max_particles};
  w_slow_ = w_fast_ = 0.0;
  computeClusters();
}

void ParticleFilter::motionUpdate(const Pose2& from, const Pose2& to) {
  const OdometryMotion motion = decomposeOdometry(from, to);
  for (auto& p : particles_) p.pose = sampleOdometryMotion(p.pose, motion, options_.motion, rng_);
}

double ParticleFilter::likelihood(const Pose2& pose,
                                  const std::vector<Eigen::Vector2d>& endpoints) const {
  // AMCL's likelihood field: each beam adds pz³ to 1, pz mixing a Gaussian of the end point's
  // distance to the nearest obstacle with a uniform of the sensor's range (the cube is AMCL's
  // own, to sharpen the sum).
  const double z_hit_denominator = 2.0 * options_.sigma_hit * options_.sigma_hit;
  const double z_rand_share = options_.z_rand / options_.max_range;
  double p = 1.0;
  for (const auto& e : endpoints) {
    const double z = map_.distance(pose.apply(e));
    const double pz = options_.z_hit * std::exp(-z * z / z_hit_denominator) + z_rand_share;
    p += pz * pz * pz;
  }
  return p;
}

void ParticleFilter::sensorUpdate(const std::vector<Eigen::Vector2d>& all_endpoints) {
  if (particles_.empty() || all_endpoints.empty()) return;
  // AMCL's beam subsampling: every step-th beam, step = (n − 1) / (max_beams − 1).
  std::vector<Eigen::Vector2d> endpoints;
  const std::size_t n = all_endpoints.size();
  const std::size_t step = std::max<std::size_t>(1, (n - 1) / std::max(1, options_.max_beams - 1));
  for (std::size_t i = 0; i < n; i += step) endpoints.push_back(all_endpoints[i]);
  double total = 0.0;
  for (auto& p : particles_) {
    p.weight *= likelihood(p.pose, endpoints);
    total += p.weight;
  }
  if (total <= 0.0) {
    for (auto& p : particles_) p.weight = 1.0 / particles_.size();
    return;
  }
  double w_avg = 0.0;
  for (auto& p : particles_) {
    w_avg += p.weight;
    p.weight /= total;
  }
  w_avg /= double(particles_.size());
  w_slow_ = w_slow_ == 0.0 ? w_avg : w_slow_ + options_.alpha_slow * (w_avg - w_slow_);
  w_fast_ = w_fast_ == 0.0 ? w_avg : w_fast_ + options_.alpha_fast * (w_avg - w_fast_);
}

int ParticleFilter::kldLimit(int k) const {
  if (k <= 1) return options_.max_particles;
  const double b = 2.0 / (9.0 * (k - 1));
  const double x = 1.0 - b + std::sqrt(b) * options_.kld_z;
  const int n = int(std::ceil((k - 1) / (2.0 * options_.kld_err) * x * x * x));
  return std::clamp(n, options_.min_particles, options_.max_particles);
}

void ParticleFilter::resample() {
  if (particles_.empty()) return;
  const double w_diff =
      w_slow_ > 0.0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;  // share drawn at random
  std::vector<double> cumulative(particles_.size() + 1, 0.0);
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    cumulative[i + 1] = cumulative[i] + particles_[i].weight;
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Particle> drawn;
  std::unordered_set<std::int64_t> bins;
  while (int(drawn.size()) < options_.max_particles) {
    Pose2 pose;
    if (unit(rng_) < w_diff) {
      pose = randomFreePose();
    } else {
      const double r = unit(rng_) * cumulative.back();
      const auto it = std::upper_bound(cumulative.begin() + 1, cumulative.end(), r);
      pose = particles_[std::min<std::size_t>(it - cumulative.begin() - 1, particles_.size() - 1)]
                 .pose;
    }
    drawn.push_back({pose, 1.0});
    bins.insert(pack({int(std::floor(pose.x / options_.bin_size)),
                      int(std::floor(pose.y / options_.bin_size)),
                      int(std::floor(pose.yaw / options_.bin_angle))}));
    // AMCL stops once past the KLD bound for the bins occupied so far.
    if (int(drawn.size()) > kldLimit(int(bins.size()))) break;
  }
  // AMCL resets the averages after injecting, lest it spiral into complete randomness.
  if (w_diff > 0.0) w_slow_ = w_fast_ = 0.0;
  for (auto& p : drawn) p.weight = 1.0 / drawn.size();
  particles_ = std::move(drawn);
  computeClusters();
}

void ParticleFilter::computeClusters() {
  // Occupied bins, then connected groups of them (26-neighbourhood), as AMCL's kd-tree does.
  std::unordered_map<std::int64_t, int> bin_of_key;
  std::vector<BinKey> keys;
  std::vector<int> bin_of_particle(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Pose2& pose = particles_[i].pose;
    const BinKey key{int(std::floor(pose.x / options_.bin_size)),
                     int(std::floor(pose.y / options_.bin_size)),
                     int(std::floor(pose.yaw / options_.bin_angle))};
    const auto [it, added] = bin_of_key.emplace(pack(key), int(keys.size()));
    if (added) keys.push_back(key);
    bin_of_particle[i] = it->second;
  }
  std::vector<int> cluster_of_bin(keys.size(), -1);
  int clusters = 0;
  for (std::size_t b = 0; b < keys.size(); ++b) {
    if (cluster_of_bin[b] >= 0) continue;
    std::vector<int> stack{int(b)};
    cluster_of_bin[b] = clusters;
    while (!stack.empty()) {
      const BinKey key = keys[stack.back()];
      stack.pop_back();
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int da = -1; da <= 1; ++da) {
            const auto it = bin_of_key.find(pack({key[0] + dx, key[1] + dy, key[2] + da}));
            if (it == bin_of_key.end() || cluster_of_bin[it->second] >= 0) continue;
            cluster_of_bin[it->second] = clusters;
            stack.push_back(it->second);
          }
        }
      }
    }
    ++clusters;
  }
  // Weighted statistics per cluster: mean and covariance of x, y; circular mean of yaw.
  struct Sums {
    double w = 0.0, x = 0.0, y = 0.0, xx = 0.0, xy = 0.0, yy = 0.0, c = 0.0, s = 0.0;
    int count = 0;
  };
  std::vector<Sums> sums(clusters);
  double total = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Particle& p = particles_[i];
    Sums& s = sums[cluster_of_bin[bin_of_particle[i]]];
    s.w += p.weight;
    s.x += p.weight * p.pose.x;
    s.y += p.weight * p.pose.y;
    s.xx += p.weight * p.pose.x * p.pose.x;
    s.xy += p.weight * p.pose.x * p.pose.y;
    s.yy += p.weight * p.pose.y * p.pose.y;
    s.c += p.weight * std::cos(p.pose.yaw);
    s.s += p.weight * std::sin(p.pose.yaw);
    ++s.count;
    total += p.weight;
  }
  clusters_.clear();
  for (const Sums& s : sums) {
    if (s.w <= 0.0) continue;
    ParticleCluster c;
    c.weight = total > 0.0 ? s.w / total : 0.0;
    c.count = s.count;
    c.mean = {s.x / s.w, s.y / s.w, std::atan2(s.s, s.c)};
    c.covariance << s.xx / s.w - c.mean.x * c.mean.x, s.xy / s.w - c.mean.x * c.mean.y,
        s.xy / s.w - c.mean.x * c.mean.y, s.yy / s.w - c.mean.y * c.mean.y;
    const double resultant = std::min(1.0, std::hypot(s.c, s.s) / s.w);
    c.yaw_variance = resultant > 0.0 ? -2.0 * std::log(resultant) : INFINITY;
    clusters_.push_back(c);
  }
  std::sort(clusters_.begin(), clusters_.end(),
            [](const auto& a, const auto& b) { return a.weight > b.weight; });
}

}  // namespace isg::slam
