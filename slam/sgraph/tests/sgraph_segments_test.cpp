// The map's segments as its diagnostics tell them: which keyframes belong to a segment that ended,
// so that a report places them by where the localizer had them then (docs/deviations.md).
#include <gtest/gtest.h>

#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

TEST(SGraphSegments, TheDiagnosticsSayWhichKeyframesAreOfASegmentThatEnded) {
  SGraph graph = testing::boxSGraph(4.0);
  const MapDiagnostics walked = graph.diagnostics();
  ASSERT_GE(walked.keyframes.size(), 3u);  // a keyframe a metre
  EXPECT_EQ(walked.current_segment, 0u);
  for (const auto& kf : walked.keyframes) EXPECT_EQ(kf.segment, 0);
  graph.startNewSegment(walked.keyframes.back().stamp, "a test");
  const MapDiagnostics ended = graph.diagnostics();
  ASSERT_EQ(ended.keyframes.size(), walked.keyframes.size());
  EXPECT_EQ(ended.current_segment, walked.keyframes.size());
  for (std::size_t k = 0; k < ended.keyframes.size(); ++k) {
    EXPECT_EQ(ended.keyframes[k].segment, 0) << k;
    EXPECT_DOUBLE_EQ(ended.keyframes[k].stamp, walked.keyframes[k].stamp) << k;
  }
  EXPECT_TRUE(ended.walls.empty());  // the current segment has seen nothing yet
}

}  // namespace
}  // namespace isg::slam
