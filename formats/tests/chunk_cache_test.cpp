#include "formats/chunk_cache.hpp"

#include <gtest/gtest.h>

#include <string>

namespace isg::formats {
namespace {

// The chunks held stay within their budget of bytes and of chunks, the least recently used going
// first; the chunk just read is held even when it alone fills the budget.
TEST(ChunkCache, HoldsWithinItsBytesLeastRecentlyUsedFirst) {
  ChunkCache cache(8, 100);
  cache.insert(0, std::string(40, 'a'));
  cache.insert(1, std::string(40, 'b'));
  ASSERT_NE(cache.find(0), nullptr);  // 0 is now the more recently used
  EXPECT_EQ(cache.insert(2, std::string(40, 'c')), std::string(40, 'c'));
  EXPECT_EQ(cache.heldBytes(), 80u);
  EXPECT_EQ(cache.find(1), nullptr);  // let go: the least recently used
  EXPECT_NE(cache.find(0), nullptr);
  cache.makeRoom(90);  // before decompressing a chunk of 90: the others go
  EXPECT_EQ(cache.heldChunks(), 0u);
  EXPECT_EQ(cache.insert(3, std::string(150, 'd')).size(), 150u);  // alone, past the budget
  EXPECT_EQ(cache.heldBytes(), 150u);
  cache.insert(4, std::string(10, 'e'));
  EXPECT_EQ(cache.find(3), nullptr);
  EXPECT_EQ(cache.heldBytes(), 10u);
}

TEST(ChunkCache, HoldsAtMostItsCountOfChunks) {
  ChunkCache cache(2, 1000);
  for (std::uint32_t k = 0; k < 5; ++k) cache.insert(k, std::string(1, char('a' + k)));
  EXPECT_EQ(cache.heldChunks(), 2u);
  EXPECT_NE(cache.find(4), nullptr);
  EXPECT_NE(cache.find(3), nullptr);
  EXPECT_EQ(cache.find(2), nullptr);
}

}  // namespace
}  // namespace isg::formats
