#include "sim/imu_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/angles.hpp"
#include "formats/dataset_format.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

double angleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

bim::ImuConfig noiseless(const std::array<double, 6>& mount) {
  bim::ImuConfig config;
  config.mount = mount;
  config.gyroscope_noise_density = config.gyroscope_random_walk = 0.0;
  config.accelerometer_noise_density = config.accelerometer_random_walk = 0.0;
  return config;
}

// An IMU off the base's origin and tilted, so that the lever arm and the mount's rotation count.
constexpr std::array<double, 6> kOffsetMount = {0.2, -0.1, 0.3, 0.1, -0.05, 0.4};

void expectDerivativesOfThePose(const BaseMotion& t) {
  const double h = 1e-4;
  for (double s = h; s < t.duration() - h; s += 0.037) {
    const BaseKinematics k = t.kinematics(s);
    const Eigen::Isometry3d before = t.pose(s - h), after = t.pose(s + h);
    const Eigen::Vector3d velocity = (after.translation() - before.translation()) / (2 * h);
    const Eigen::Vector3d acceleration =
        (after.translation() - 2 * k.B_T_R.translation() + before.translation()) / (h * h);
    const Eigen::AngleAxisd turn(before.linear().transpose() * after.linear());
    const Eigen::Vector3d angular_velocity = turn.angle() * turn.axis() / (2 * h);
    const Eigen::Vector3d angular_acceleration =
        (t.kinematics(s + h).angular_velocity - t.kinematics(s - h).angular_velocity) / (2 * h);
    EXPECT_LT((k.velocity - velocity).norm(), 1e-6) << s;
    EXPECT_LT((k.acceleration - acceleration).norm(), 2e-3) << s;
    EXPECT_LT((k.angular_velocity - angular_velocity).norm(), 1e-5) << s;
    EXPECT_LT((k.angular_acceleration - angular_acceleration).norm(), 1e-5) << s;
  }
}

TEST(BaseKinematics, AreTheDerivativesOfThePose) {
  expectDerivativesOfThePose(BaseMotion({{0, 0}, {3, 0}, {3, 2}, {1, 3}}, 0.4, 0.5, 1.0, {}));
}

// A person's walk with the sensors in hand, head turns at fixed phases.
GaitConfig walkersGait() {
  GaitConfig walker;
  walker.handheld = true;
  walker.bob_m = 0.025;
  walker.sway_m = 0.025;
  walker.head_turn_deg = 15.0;
  walker.head_phases = {0.3, 2.1};
  walker.standing_height = kHandheldHeight;
  walker.turn_rate = kHandheldTurnRate;
  return walker;
}

TEST(BaseKinematics, AWalkersSwayAndHeadTurnsToo) {
  const GaitConfig walker = walkersGait();
  const BaseMotion t({{0, 0}, {3, 0}, {3, 2}, {1, 3}}, 0.4, 0.8, 0.0, walker);
  expectDerivativesOfThePose(t);
  // Mid-way along the first straight: held 1.2 m up (± the bob), within the sway of the way and
  // turned about it by the head turns (at most 15°).
  const double mid = 0.5 * (t.arrival(0, 0) + t.arrival(0, 1));
  const Eigen::Isometry3d pose = t.pose(mid);
  EXPECT_NEAR(pose.translation().z(), kHandheldHeight, 0.025 + 1e-9);
  EXPECT_NEAR(pose.translation().y(), 0.0, 0.025 + 1e-9);
  EXPECT_LE(std::abs(common::yawOf(pose.linear())), 15.0 * std::numbers::pi / 180 + 1e-9);
  // The head does turn: over the straight the yaw spans several degrees.
  double lo = 1e9, hi = -1e9;
  for (double s = t.arrival(0, 0) + 1.0; s < t.arrival(0, 1) - 1.0; s += 0.05) {
    const double yaw = common::yawOf(t.pose(s).linear());
    lo = std::min(lo, yaw), hi = std::max(hi, yaw);
  }
  EXPECT_GT((hi - lo) * 180 / std::numbers::pi, 5.0);
}

TEST(BaseKinematics, AReplayedWalkToo) {
  // A walk recorded at 10 Hz: a slow S through the plane with a stop from 6 to 9 s, carried by
  // hand.
  std::vector<bim::WalkPose> walk;
  for (int i = 0; i <= 150; ++i) {
    const double t = 0.1 * i, s = t < 6.0 ? t : t < 9.0 ? 6.0 : t - 3.0;
    walk.push_back({t, {0.6 * s, 1.5 * std::sin(0.5 * s)}, 0.0, i + 1});
  }
  const GaitConfig walker = walkersGait();
  const BaseMotion t(std::make_shared<const WalkPath>(walk, false, kHandheldTurnRate), 0.5, walker);
  EXPECT_NEAR(t.duration(), 15.0, 1e-12);
  expectDerivativesOfThePose(t);
  // Standing (7.5 s): no gait, the sensors 1.2 m above the floor at 0.5 m, still but for the
  // spline's ringing after a stop from 0.6 m/s in no time.
  EXPECT_NEAR(t.pose(7.5).translation().z(), 0.5 + kHandheldHeight, 1e-3);
  EXPECT_LT(t.kinematics(7.5).velocity.norm(), 0.03);
}

TEST(BaseKinematics, ASensorsPathTooWithTheBaseRigidWithTheSensor) {
  // A hand-held camera's path at 30 Hz: an S at 0.8 m/s, the camera 1.3 m up and bobbing, looking
  // ahead as cameras do (rolled −90° about its x, so that its z looks along the walk), its yaw
  // swinging ±20° about the way ahead; the base 0.1 m behind and 0.2 m below it, turned.
  std::vector<bim::WalkPose> walk;
  for (int i = 0; i <= 300; ++i) {
    const double t = i / 30.0, s = 0.8 * t;
    const double heading = std::atan2(1.5 * 0.5 * std::cos(0.5 * s), 1.0);
    bim::WalkPose pose{t, {s, 1.5 * std::sin(0.5 * s)}, heading + 0.35 * std::sin(1.3 * t), i + 1};
    pose.z = 1.3 + 0.02 * std::sin(2.0 * std::numbers::pi * 1.8 * t);
    pose.roll = -0.5 * std::numbers::pi + 0.05 * std::sin(0.9 * t);
    pose.pitch = 0.1 * std::sin(0.7 * t);
    walk.push_back(pose);
  }
  Eigen::Isometry3d S_T_R = Eigen::Isometry3d::Identity();
  S_T_R.translation() = Eigen::Vector3d(-0.1, 0.2, 0.05);
  S_T_R.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const BaseMotion t(std::make_shared<const WalkPath>(walk, true, kHandheldTurnRate, true), 0.5,
                     walkersGait(), S_T_R);
  expectDerivativesOfThePose(t);
  // The sensor (B_T_R · R_T_S) is where the file says, within the fit's millimetres.
  double worst = 0.0, worst_angle = 0.0;
  for (const auto& pose : walk) {
    if (pose.t < 0.2 || pose.t > 9.8) continue;
    const Eigen::Isometry3d B_T_S = t.pose(pose.t) * S_T_R.inverse();
    const Eigen::Vector3d file(pose.xy.x(), pose.xy.y(), 0.5 + pose.z);
    worst = std::max(worst, (B_T_S.translation() - file).norm());
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pose.pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    worst_angle = std::max(worst_angle, Eigen::AngleAxisd(R.transpose() * B_T_S.linear()).angle());
  }
  EXPECT_LT(worst, 0.002);
  EXPECT_LT(worst_angle * 180 / std::numbers::pi, 0.1);
}

TEST(BaseKinematics, OnAFlightOfStairsTooWithTheBodyTiltedToTheSlope) {
  // Up a 3.2 m flight over 4.5 m, along the landing, and down a steeper one over 3.6 m.
  const BaseMotion t({{0, 0, 0}, {1, 0, 0}, {5.5, 0, 3.2}, {6.5, 0, 3.2}, {6.5, 3.6, 0}}, 0.0, 0.5,
                     {});
  expectDerivativesOfThePose(t);
  // Mid-flight the body stands 0.46 m above the line of the steps and pitches nose up by its
  // slope (atan(3.2 / 4.5) = 35.4°), give or take the trot's 2°; it walks at kStairSpeed.
  const double mid = 0.5 * (t.arrival(0, 1) + t.arrival(0, 2));
  const Eigen::Isometry3d pose = t.pose(mid);
  EXPECT_NEAR(pose.translation().x(), 3.25, 1e-9);
  EXPECT_NEAR(pose.translation().z(), 1.6 + 0.46, 0.02);
  const Eigen::Vector3d forward = pose.linear().col(0);
  EXPECT_NEAR(std::atan2(forward.z(), forward.head<2>().norm()) * 180 / std::numbers::pi, 35.42,
              2.1);
  EXPECT_NEAR(t.kinematics(mid).velocity.head<2>().norm(), kStairSpeed, 1e-9);
  EXPECT_NEAR(t.planar(mid).floor_rate, kStairSpeed * 3.2 / 4.5, 1e-9);
  // On the landing it is level again and 3.2 m higher.
  const double landing = 0.5 * (t.arrival(0, 2) + t.arrival(0, 3));
  EXPECT_NEAR(t.planar(landing).incline, 0.0, 1e-12);
  EXPECT_NEAR(t.planar(landing).floor_z, 3.2, 1e-12);
  EXPECT_NEAR(t.planar(t.duration()).floor_z, 0.0, 1e-12);
}

TEST(Imu, AtRestItReadsGravityUpwardsAndNoRotation) {
  GaitConfig gait;
  const BaseMotion t({{1, 1}}, 0.7, 0.5, 0.0, gait);  // one waypoint: it stands
  const Eigen::Isometry3d R_T_I = sensors::mountTransform({0, 0, 0, 0, 0, std::numbers::pi / 2});
  const ImuSample s = idealImuSample(t, R_T_I, 9.81, 3.0);
  EXPECT_LT((s.accelerometer - Eigen::Vector3d(0, 0, 9.81)).norm(), 1e-12);
  EXPECT_LT(s.gyroscope.norm(), 1e-12);
  // Rolled 90° about x, its y axis points down: it reads -g along y.
  const ImuSample rolled =
      idealImuSample(t, sensors::mountTransform({0, 0, 0, std::numbers::pi / 2, 0, 0}), 9.81, 3.0);
  EXPECT_LT((rolled.accelerometer - Eigen::Vector3d(0, 9.81, 0)).norm(), 1e-12);
}

class D1Imu : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim_ = new Simulation(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  }
  static void TearDownTestSuite() { delete sim_; }
  static Simulation* sim_;
};
Simulation* D1Imu::sim_ = nullptr;

// Orientation of I in B from integrating the noiseless gyroscope over the whole run, starting
// from the true one: within 1 mrad of ground truth throughout.
TEST_F(D1Imu, IntegratedGyroscopeFollowsTheTrueOrientation) {
  const BaseMotion& t = sim_->baseMotion();
  const auto samples = simulateImu(t, noiseless(kOffsetMount), t.duration(), 1);
  const Eigen::Matrix3d R_R_I = sensors::mountTransform(kOffsetMount).linear();
  Eigen::Matrix3d B_R_I = t.pose(0.0).linear() * R_R_I;
  double worst = 0.0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const double dt = samples[k].t - samples[k - 1].t;
    B_R_I = B_R_I * expSO3(0.5 * (samples[k - 1].gyroscope + samples[k].gyroscope) * dt);
    worst = std::max(worst, angleBetween(B_R_I, t.pose(samples[k].t).linear() * R_R_I));
  }
  EXPECT_GT(t.duration(), 40.0);
  EXPECT_LT(worst, 1e-3);
  RecordProperty("worst_angle_rad", std::to_string(worst));
}

// Over every 1 s window (starting each 0.5 s), the noiseless accelerometer, rotated by the true
// orientation with gravity taken out and integrated twice from the true velocity, moves the IMU
// as far as ground truth does: within 1 cm.
TEST_F(D1Imu, DoubleIntegratedAccelerometerMatchesTheDisplacement) {
  const BaseMotion& t = sim_->baseMotion();
  const double g = 9.81;
  const auto samples = simulateImu(t, noiseless(kOffsetMount), t.duration(), 1);
  const Eigen::Isometry3d R_T_I = sensors::mountTransform(kOffsetMount);
  auto imuPosition = [&](double s) -> Eigen::Vector3d { return (t.pose(s) * R_T_I).translation(); };
  auto worldAcceleration = [&](const ImuSample& s) -> Eigen::Vector3d {
    return t.pose(s.t).linear() * R_T_I.linear() * s.accelerometer - Eigen::Vector3d(0, 0, g);
  };
  const std::size_t window = 200;  // 1 s at 200 Hz
  double worst = 0.0;
  int windows = 0;
  for (std::size_t first = 0; first + window < samples.size(); first += window / 2, ++windows) {
    const BaseKinematics k = t.kinematics(samples[first].t);
    Eigen::Vector3d velocity =
        k.velocity + k.B_T_R.linear() * k.angular_velocity.cross(R_T_I.translation());
    Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
    for (std::size_t i = first; i < first + window; ++i) {
      const double dt = samples[i + 1].t - samples[i].t;
      const Eigen::Vector3d a0 = worldAcceleration(samples[i]);
      const Eigen::Vector3d a1 = worldAcceleration(samples[i + 1]);
      // Exact for an acceleration linear over the step.
      displacement += velocity * dt + (2 * a0 + a1) / 6 * dt * dt;
      velocity += (a0 + a1) / 2 * dt;
    }
    const Eigen::Vector3d truth =
        imuPosition(samples[first + window].t) - imuPosition(samples[first].t);
    worst = std::max(worst, (displacement - truth).norm());
  }
  EXPECT_GT(windows, 80);
  EXPECT_LT(worst, 0.01);
  RecordProperty("worst_window_error_m", std::to_string(worst));
}

// Allan deviation of a stationary unit's readings (per axis, non-overlapping clusters of `m`).
std::vector<double> allanDeviation(const std::vector<ImuSample>& samples, bool gyroscope,
                                   const Eigen::Vector3d& truth, std::size_t m) {
  std::vector<double> out;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> means;
    for (std::size_t first = 0; first + m <= samples.size(); first += m) {
      double sum = 0.0;
      for (std::size_t i = first; i < first + m; ++i) {
        const Eigen::Vector3d& v = gyroscope ? samples[i].gyroscope : samples[i].accelerometer;
        sum += v[axis] - truth[axis];
      }
      means.push_back(sum / double(m));
    }
    double sum = 0.0;
    for (std::size_t k = 1; k < means.size(); ++k) sum += std::pow(means[k] - means[k - 1], 2);
    out.push_back(std::sqrt(sum / (2.0 * double(means.size() - 1))));
  }
  return out;
}

TEST(Imu, AllanDeviationOfWhiteNoiseAtOneSecondIsTheDensity) {
  GaitConfig gait;
  const BaseMotion still({{0, 0}}, 0.0, 0.5, 0.0, gait);
  bim::ImuConfig config;
  config.gyroscope_random_walk = config.accelerometer_random_walk = 0.0;
  const auto samples = simulateImu(still, config, 3000.0, 7);
  // For white noise of density σ, the Allan deviation is σ / √τ: σ itself at τ = 1 s.
  for (double adev : allanDeviation(samples, true, Eigen::Vector3d::Zero(), 200)) {
    EXPECT_NEAR(adev, config.gyroscope_noise_density, 0.1 * config.gyroscope_noise_density);
  }
  for (double adev : allanDeviation(samples, false, Eigen::Vector3d(0, 0, 9.81), 200)) {
    EXPECT_NEAR(adev, config.accelerometer_noise_density, 0.1 * config.accelerometer_noise_density);
  }
}

TEST(Imu, BiasRandomWalkGrowsAsConfigured) {
  GaitConfig gait;
  const BaseMotion still({{0, 0}}, 0.0, 0.5, 0.0, gait);
  bim::ImuConfig config;  // the defaults, at 50 Hz to keep the run short
  config.rate_hz = 50.0;
  const auto samples = simulateImu(still, config, 6000.0, 3);
  // White noise plus a random walk of strength σ_b: ADEV(τ)² = σ²/τ + σ_b² τ / 3.
  const double tau = 50.0;
  auto expected = [tau](double density, double walk) {
    return std::sqrt(density * density / tau + walk * walk * tau / 3.0);
  };
  // 120 clusters per axis: the estimate's own spread is ~1/√(2·119) ≈ 6.5 %; three axes pooled.
  auto pooled = [](const std::vector<double>& per_axis) {
    double sum = 0.0;
    for (double a : per_axis) sum += a * a;
    return std::sqrt(sum / double(per_axis.size()));
  };
  const double gyro = pooled(allanDeviation(samples, true, Eigen::Vector3d::Zero(), 2500));
  const double accel = pooled(allanDeviation(samples, false, Eigen::Vector3d(0, 0, 9.81), 2500));
  EXPECT_NEAR(gyro, expected(config.gyroscope_noise_density, config.gyroscope_random_walk),
              0.15 * expected(config.gyroscope_noise_density, config.gyroscope_random_walk));
  EXPECT_NEAR(
      accel, expected(config.accelerometer_noise_density, config.accelerometer_random_walk),
      0.15 * expected(config.accelerometer_noise_density, config.accelerometer_random_walk));
}

TEST(Imu, SameSeedSameBytes) {
  GaitConfig gait;
  const BaseMotion t({{0, 0}, {2, 0}, {2, 2}}, 0.0, 0.5, 0.0, gait);
  bim::ImuConfig config;
  const std::string a = formats::dataset::imuText(simulateImu(t, config, t.duration(), 5));
  const std::string b = formats::dataset::imuText(simulateImu(t, config, t.duration(), 5));
  const std::string c = formats::dataset::imuText(simulateImu(t, config, t.duration(), 6));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a.substr(0, a.find('\n')), "t,ax,ay,az,gx,gy,gz");
}

TEST(Imu, MadeAChunkAtATimeItIsTheWholeStreamBitForBit) {
  GaitConfig gait;
  const BaseMotion t({{0, 0}, {2, 0}, {2, 2}}, 0.0, 0.5, 0.0, gait);
  bim::ImuConfig config;  // noisy: the generator and the biases carry over from chunk to chunk
  const std::vector<ImuSample> whole = simulateImu(t, config, t.duration(), 5);
  ImuStream stream(t, config, t.duration(), 5);
  ASSERT_EQ(stream.size(), whole.size());
  std::vector<ImuSample> chunked;
  // Odd sizes, one of a single sample, then the rest in chunks that do not divide it.
  for (const std::size_t count : {std::size_t(1), std::size_t(7), std::size_t(1000)}) {
    const auto chunk = stream.next(count);
    EXPECT_EQ(chunk.size(), count);
    chunked.insert(chunked.end(), chunk.begin(), chunk.end());
  }
  for (std::vector<ImuSample> chunk; !(chunk = stream.next(333)).empty();) {
    chunked.insert(chunked.end(), chunk.begin(), chunk.end());
  }
  EXPECT_TRUE(stream.next(10).empty());
  EXPECT_EQ(formats::dataset::imuText(chunked), formats::dataset::imuText(whole));
  ASSERT_EQ(chunked.size(), whole.size());
  EXPECT_EQ(chunked.back().accelerometer, whole.back().accelerometer);  // bit for bit
  EXPECT_EQ(chunked.back().gyroscope, whole.back().gyroscope);
}

}  // namespace
}  // namespace isg::sim
