// The sight profile of scans laid out by hand: which returns count, in which degree, how far.

#include "slam/sight_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace isg::slam {
namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// A return at `range` horizontally toward `azimuth_deg` (in L), `z` above the sensor.
sensors::ScanPoint pointAt(double azimuth_deg, double range, double z) {
  const double a = radians(azimuth_deg);
  return {float(range * std::cos(a)), float(range * std::sin(a)), float(z), 0.0f, 0, 0.0f};
}

// The sensor 0.6 m above R's origin, turned 90° about z: L's x is R's y.
Eigen::Isometry3d mount() {
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
  R_T_L.linear() = Eigen::AngleAxisd(radians(90.0), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  R_T_L.translation() = Eigen::Vector3d(0.1, 0.0, 0.6);
  return R_T_L;
}

// A room 5 m round, seen at the sensor's height over `degrees` of L's azimuth from 0.
sensors::Scan ring(int degrees) {
  sensors::Scan scan;
  for (int d = 0; d < degrees; ++d) scan.points.push_back(pointAt(d + 0.5, 5.0, 0.0));
  return scan;
}

TEST(SightProfile, KeepsTheFarthestReturnInTheBandPerDegreeOfTheBasesAzimuth) {
  sensors::Scan scan = ring(360);
  scan.points.push_back(pointAt(10.5, 12.0, 0.2));   // through a door: farther
  scan.points.push_back(pointAt(20.5, 30.0, -3.0));  // down a stairwell: below the band
  scan.points.push_back(pointAt(30.5, 9.0, 2.0));    // up through an opening: above it
  scan.points.push_back(pointAt(40.5, 7.0, -0.55));  // the floor beyond a gap: in the band
  // The band: 0.05 m (the floor, 0.05 m below R's origin, less 0.1 m) to 2.05 m above R's origin.
  const SightProfile profile = sightProfile(scan, mount(), -0.05, 2.05);
  ASSERT_EQ(profile.range_cm.size(), std::size_t(SightProfile::kBins));
  EXPECT_EQ(profile.sensor_R, Eigen::Vector3d(0.1, 0.0, 0.6));
  // L's azimuth a is R's a + 90°.
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(100.5)), 12.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(110.5)), 5.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(120.5)), 5.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(130.5)), 7.0);
  // Any turn of the same direction.
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(100.5 - 360.0)), 12.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(100.5 + 720.0)), 12.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(-0.5)), 5.0);
}

TEST(SightProfile, ADegreeWithNoReturnInAScanThatSawMostIsOutOfRange) {
  // Returns over 270° of L's azimuth: L's 270°–360° (R's 0°–90°) met nothing.
  const SightProfile profile = sightProfile(ring(270), mount(), -0.05, 2.05);
  EXPECT_EQ(profile.rangeToward(radians(45.0)), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(180.5)), 5.0);
}

// Out through an opening to the outside: the near-level beams meet nothing, the ones pointing down
// meet the floor short of the opening. The farthest return there is the floor's; the degree is
// out of range all the same.
TEST(SightProfile, ADegreeWhoseOnlyReturnsAreTheFloorShortOfAnOpeningIsOutOfRange) {
  sensors::Scan scan;
  for (int d = 0; d < 360; ++d) {
    // The floor 0.6 m below the sensor, met 2.2 and 3.8 m off by beams 15° and 9° down.
    scan.points.push_back(pointAt(d + 0.5, 2.2, -0.6));
    scan.points.push_back(pointAt(d + 0.5, 3.8, -0.6));
    // The walls 5 m round, but for L's 100°–119°, an opening; a beam 1.5° down still returns.
    if (d < 100 || d >= 120) scan.points.push_back(pointAt(d + 0.5, 5.0, d == 130 ? -0.13 : 0.0));
  }
  const SightProfile profile = sightProfile(scan, mount(), -0.05, 2.05);
  // L's azimuth a is R's a + 90°: the opening is R's 190°–209°.
  EXPECT_EQ(profile.rangeToward(radians(195.5)), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(185.5)), 5.0);
  EXPECT_DOUBLE_EQ(profile.rangeToward(radians(220.5)), 5.0);  // 1.5° down is near level
  // A scan whose near-level beams returned in fewer than half its degrees (no ring near level)
  // keeps the floor's range: it cannot tell.
  sensors::Scan floor_only;
  for (const auto& p : scan.points) {
    if (p.z < -0.5f) floor_only.points.push_back(p);
  }
  const SightProfile floor_profile = sightProfile(floor_only, mount(), -0.05, 2.05);
  EXPECT_DOUBLE_EQ(floor_profile.rangeToward(radians(195.5)), 3.8);
}

TEST(SightProfile, AScanThatSawTooLittleSeesPastNothing) {
  // Returns in 170 of 360 degrees: fewer than half.
  const SightProfile profile = sightProfile(ring(170), mount(), -0.05, 2.05);
  ASSERT_FALSE(profile.empty());
  for (double a = 0.5; a < 360.0; a += 1.0) EXPECT_EQ(profile.rangeToward(radians(a)), 0.0) << a;
  // And a profile never recorded says nothing either.
  EXPECT_EQ(SightProfile().rangeToward(0.0), 0.0);
}

}  // namespace
}  // namespace isg::slam
