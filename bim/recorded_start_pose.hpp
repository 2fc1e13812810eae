#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

namespace isg::bim {

// A run's start pose as the floor-plan benchmark gives it (docs/benchmark.md): a CSV table, one
// row per recorded run — "SEQUENCE,PLAN.png,STAMP,tx,ty,tz,qx,qy,qz,qw" after a '#' header —, the
// pose of the recording's tracked sensor (the walk file's frame) in the plan frame at STAMP, in
// the recording's own clock (about 5 s after its start).
struct RecordedStartPose {
  std::string sequence;
  std::string plan_file;                                   // the second column, as written
  double stamp = 0.0;                                      // in the recording's clock
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the sensor's, in the plan frame
  int line = 0;                                            // in the table, from 1
};

// The table is small (one row a run); anything larger is not one.
inline constexpr std::uintmax_t kMaxStartPoseTableBytes = 16u << 20;

// Reads the row of `sequence` from the table at `path`. Fields may have blanks around them; lines
// starting with '#' and blank lines are skipped. InputError (the file, "line N" where a row is
// wrong) when the file cannot be read, a row is malformed (not 10 fields, a number that is not
// one, a quaternion not of unit length), the sequence is in it twice, or it is not in it (the
// message lists the sequences the table has).
RecordedStartPose readRecordedStartPose(const std::string& path, const std::string& sequence);

}  // namespace isg::bim
