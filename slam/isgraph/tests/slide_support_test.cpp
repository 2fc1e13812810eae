// keepBestSupported: a long corridor's slides, kept by the wall length that proposes them.
#include "slam/isgraph/slide_support.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

// Hypotheses whose x is their slide (y, yaw unused here), one per distinct slide.
std::vector<Eigen::Vector3d> hypothesesAt(const std::vector<std::pair<int, double>>& slides) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& [turn, slide] : slides) out.emplace_back(slide, double(turn), 0.0);
  return out;
}

TEST(SlideSupport, KeepsTheSlidesMostWallProposesInTheirOrder) {
  // Five slides, turn 0 but the last. Proposals: 4 m of wall at 10.0 (two walls, one at 10.05:
  // within the 0.3 m tolerance), 2 m at 3.0, 1 m at 7.0, 1 m at 20.0 (turn 1), and 10.2 (0.5 m).
  const std::vector<std::pair<int, double>> slides = {
      {0, 7.0}, {0, 10.0}, {0, 3.0}, {0, 10.2}, {1, 20.0}};
  const std::vector<SlideProposal> proposals = {{0, 7.0, 1.0}, {0, 10.0, 2.5}, {0, 10.05, 1.5},
                                                {0, 3.0, 2.0}, {0, 10.2, 0.5}, {1, 20.0, 1.0}};
  // Support: 7.0 → 1; 10.0 → 2.5 + 1.5 + 0.5 = 4.5; 3.0 → 2; 10.2 → 4.5 (10.0 and 10.05 are
  // within 0.3 m of it too); 20.0 → 1 (turn 1 only: 10.0 of turn 0 is not counted).
  auto kept = hypothesesAt(slides);
  keepBestSupported(kept, slides, proposals, 3, 0.3);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_DOUBLE_EQ(kept[0].x(), 10.0);  // the order found is kept
  EXPECT_DOUBLE_EQ(kept[1].x(), 3.0);
  EXPECT_DOUBLE_EQ(kept[2].x(), 10.2);
  // Keep 4: 7.0 and 20.0 tie at 1 m; the earlier (7.0) is kept.
  kept = hypothesesAt(slides);
  keepBestSupported(kept, slides, proposals, 4, 0.3);
  ASSERT_EQ(kept.size(), 4u);
  EXPECT_DOUBLE_EQ(kept[0].x(), 7.0);
  EXPECT_DOUBLE_EQ(kept[3].x(), 10.2);
}

TEST(SlideSupport, NoMoreThanKeepLeavesThemAsTheyAre) {
  const std::vector<std::pair<int, double>> slides = {{0, 1.0}, {1, 2.0}};
  auto kept = hypothesesAt(slides);
  keepBestSupported(kept, slides, {{0, 1.0, 1.0}}, 2, 0.3);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_DOUBLE_EQ(kept[0].x(), 1.0);
  EXPECT_DOUBLE_EQ(kept[1].x(), 2.0);
}

// The edge of the tolerance counts: a proposal exactly `tolerance` away supports the slide.
TEST(SlideSupport, AProposalAtTheToleranceCounts) {
  const std::vector<std::pair<int, double>> slides = {{0, 0.0}, {0, 5.0}};
  const std::vector<SlideProposal> proposals = {{0, 0.0, 1.0}, {0, 5.0, 1.5}, {0, 0.25, 1.0}};
  auto kept = hypothesesAt(slides);
  keepBestSupported(kept, slides, proposals, 1, 0.25);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_DOUBLE_EQ(kept[0].x(), 0.0);  // 2 m against 1.5 m
}

}  // namespace
}  // namespace isg::slam
