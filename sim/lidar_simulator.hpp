#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "bim/scenario.hpp"
#include "sensors/lidar_model.hpp"
#include "sensors/messages.hpp"
#include "sim/body_shadow.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scan_caster.hpp"

namespace isg::sim {

// One return of the simulated VLP-16: the localizer's own point type (sensors/messages.hpp), in the
// LiDAR frame L at its own firing instant (as the real sensor reports it: not deskewed).
using LidarPoint = sensors::ScanPoint;

// CPU seconds one turn spent in each of its stages (for the run's stage timing).
struct ScanTiming {
  double poses_s = 0.0;    // the sensor's poses and every ray's origin and direction
  double casting_s = 0.0;  // the rays against the building
  double noise_s = 0.0;    // noise, quantisation, lost returns, intensity: the points
  ScanTiming& operator+=(const ScanTiming& other) {
    poses_s += other.poses_s;
    casting_s += other.casting_s;
    noise_s += other.noise_s;
    return *this;
  }
};

struct LidarScan {
  // By the sensor's stamp convention: the turn's first firing, or the start of its last packet
  // (each point's `time` is from this stamp, so negative before it).
  double stamp = 0.0;
  std::vector<LidarPoint> points;
  int rays = 0;
  ScanTiming timing;
};

// The reflectivity of a world's surface from its material's name (worlds/mjcf_generator.cpp
// names them by kind: wall, extra_wall, floor, ceiling, door, clutter, stair); other materials,
// and geoms without one, count as clutter.
double surfaceReflectivity(const bim::SurfaceReflectivity& reflectivity, std::string_view material);

// The LiDAR of docs/simulation.md in a MuJoCo world: the scenario's model (sensors/lidar_model.hpp;
// the VLP-16 unless it says otherwise). Each laser fires from the sensor's pose at its own
// instant, so a scan taken while moving carries real motion distortion.
class LidarSimulator {
 public:
  // `groups`: the geom groups the sensor sees (the building's; never the robot's: its body
  // stops the rays it meets through `config.body_occlusion`, computed from the mount). An
  // unknown `config.model` is an std::invalid_argument (the scenario parser refuses it first).
  LidarSimulator(const MujocoWorld& world, const bim::LidarConfig& config, unsigned groups);
  const sensors::LidarModel& model() const { return model_; }

  // B_T_L(t) for t in [stamp, stamp + 1/rate]: the sensor pose in the plan frame.
  using PoseAt = std::function<Eigen::Isometry3d(double t)>;

  // One full turn whose first firing is at `start` (the cloud's stamp follows the config's
  // convention). Noise and lost returns draw from generators seeded by `seed` and the block of
  // firing sequences (kBlockSequences), so that a turn is the same whichever thread makes it, and
  // every ray draws whether or not it hits: one ray's outcome never shifts another's noise.
  LidarScan scan(double start, const PoseAt& B_T_L, std::uint64_t seed);
  // Blocks [first_block, last_block) of that turn only: its points are exactly those blocks'
  // points of the whole turn, so parts made apart and joined in order are the whole turn.
  LidarScan scanBlocks(double start, const PoseAt& B_T_L, std::uint64_t seed, int first_block,
                       int last_block);
  int blockCount() const;

  // Seconds between two clouds' first firings: 1/rate for an angle cut, the cloud's packets for a
  // cut by packet count (the head turns on: each cloud starts where the last one ended).
  double scanPeriod() const { return period_; }
  // A cloud's stamp minus its first firing: 0, or the start of its last packet.
  double stampOffset() const { return stamp_offset_; }
  // The head's azimuth (counter-clockwise from L's x axis, as Vlp16::azimuth) at a turn's first
  // firing: −cut_angle for an angle cut; where the spinning head is at `start` otherwise.
  double startAzimuth(double start) const;
  // Firing sequences in one cloud, and in one packet (the model's: a VLP-16's 24, or 12 in
  // dual-return mode, where each firing fills two data blocks).
  int sequencesPerCloud() const { return sequences_; }
  int sequencesPerPacket() const;

  static constexpr int kBlockSequences = 64;
  static constexpr int kPoseStride = 8;  // sequences between two exact poses of the sensor

  double turnDuration() const { return sequences_ * sequence_s_; }
  int raysPerTurn() const { return sequences_ * lasers_; }

  // The unit normal of the geom's surface at a point on it (boxes: the face the point lies on),
  // with the geoms where they stood when the sensor was made (the building is static).
  Eigen::Vector3d surfaceNormal(int geom, const Eigen::Vector3d& point,
                                const Eigen::Vector3d& direction) const;
  // |surfaceNormal(geom, point, direction) · direction|, the cosine of the incidence: the same
  // number, without a branch on the face for a box (every ray of every turn asks it).
  double cosIncidence(int geom, const Eigen::Vector3d& point,
                      const Eigen::Vector3d& direction) const;

 private:
  // One sub-ray of a beam (last and dual returns cast the beam's centre and its two edges).
  struct SubHit {
    double distance = -1.0;  // < 0: no hit
    double power = 0.0;      // weight × reflectivity × cos(incidence) / distance²
    double cos_incidence = 0.0;
    double lit = 0.0;  // weight × reflectivity × cos(incidence): the echo's share of intensity
  };
  struct Echo {
    double distance = -1.0;  // of the echo's strongest sub-ray
    double power = 0.0;
    double cos_incidence = 0.0;  // of its strongest sub-ray
    double lit = 0.0;
  };
  SubHit subHit(const RayCaster::Hit& hit, const Eigen::Vector3d& origin,
                const Eigen::Vector3d& direction, double weight) const;
  // The echoes a beam's sub-rays make, nearest first (at most three).
  int echoes(const SubHit* sub, int count, Echo* out) const;
  struct Firing {
    Eigen::Vector3d direction;  // unit, in L
    double time;                // from the turn's start
    bool blocked;               // by the robot's own body
    Eigen::Vector3d radial;     // the beam's origin off the axis, in L (Ouster's; else zero)
  };
  // The stages of scanBlocks. The sensor's pose sampled along the turn (positions_, rotations_)
  // and the caster prepared around it.
  void samplePoses(double start, const PoseAt& B_T_L, int first_sequence, int last_sequence,
                   const Eigen::Matrix3d& L_R_table, bool turned);
  // The rays of sequences [first, last) in B (origins_, directions_, blocked_, the beam's edges).
  void blockRays(int first, int last, const Eigen::Matrix3d& L_R_table, bool turned, bool beam);
  // Their hits (hits_, edge_hits_).
  void castRays(int rays, bool beam);
  // How a block's returns are reported: the azimuth each data block (the model's sequences per
  // block: two on a VLP-16) reports, as cos and sin of its turn from the firing table's (the
  // turn's start and the block's jitter).
  struct BlockReport {
    static constexpr int kMaxDataBlocks = kBlockSequences;
    int first = 0;  // the block's first sequence
    int sequences_per_data_block = 2;
    int data_blocks = kBlockSequences / 2;
    bool reported_turn = false;
    std::array<double, kMaxDataBlocks> report_cos{}, report_sin{};
    // A return at `range` of sequence s, laser l as the sensor reports it.
    void point(const LidarSimulator& lidar, int s, int l, double range, double lit,
               std::vector<LidarPoint>& points) const;
  };
  // The share of returns at this incidence that are detected: dropout, and grazing returns
  // fading beyond the cutoff.
  double keptProbability(double cos_incidence) const;
  // The block's returns: noise and losses drawn from the block's own stream.
  void blockReturns(const BlockReport& block, int rays, std::uint64_t seed, int index, bool beam,
                    std::vector<LidarPoint>& points);
  // Ray i's beam echoes, then the ones the mode reports (last; dual: and the strongest other).
  void beamReturns(const BlockReport& block, int i, const double n[2], const double u[2],
                   std::vector<LidarPoint>& points) const;
  // A laser's origin in L (off the optical centre: the VLP-16's vertical offsets).
  Eigen::Vector3d laserOrigin(int laser) const;
  const MujocoWorld& world_;
  bim::LidarConfig config_;
  const sensors::LidarModel& model_;
  int lasers_;
  std::vector<double> laser_height_;  // each laser's origin above the optical centre, m
  double sequence_s_;                 // one firing sequence at the scenario's rate
  double quantum_;                    // the model's range steps
  double half_divergence_;
  RayCaster caster_;
  ScanCaster scan_caster_;
  int sequences_;
  double period_;
  double stamp_offset_;
  BodyShadow body_;
  std::vector<float> reflectivity_;  // per geom, from its kind of surface
  double min_signal_;       // reflectivity × cos(incidence) / range² of the weakest return
  double full_return_cos_;  // cos(grazing cutoff): returns at least this square all come
  struct GeomShape {
    int type = 0;
    bool upright = false;  // a box turned about z only: R's z row and column are exactly (0, 0, 1)
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns: the geom's axes in B
    Eigen::Vector3d inverse_half = Eigen::Vector3d::Zero();
  };
  std::vector<GeomShape> shapes_;  // per geom, at construction
  // The firing table: every (sequence, laser)'s direction and instant, computed once, so that no
  // ray calls a trigonometric function.
  std::vector<Firing> firings_;
  // Scratch space of scan(), kept to avoid allocating every turn.
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Matrix3d> rotations_;
  std::vector<Eigen::Vector3d> origins_, directions_;
  std::vector<RayCaster::Hit> hits_;
  // Last and dual returns: the beam's edge rays (left and right of the centre).
  std::vector<Eigen::Vector3d> edge_directions_[2];
  std::vector<RayCaster::Hit> edge_hits_[2];
  std::vector<char> blocked_;  // per ray of a block, when the turn starts off azimuth 0
  // A block's draws, in ray order: each ray's normal noise and uniform loss draws (two of each
  // for last and dual returns).
  std::vector<double> draws_normal_, draws_uniform_;
};

}  // namespace isg::sim
