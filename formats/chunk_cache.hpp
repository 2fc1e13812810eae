#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace isg::formats {

// What a recording's chunks may cost (docs/formats.md, "Limits of recordings"). A chunk's declared
// uncompressed size is checked against kMaxChunkBytes before anything is allocated for it, and
// decompression stops at the declared size: a few kB of compressed zeros that claim gigabytes are
// refused at once. Writers close chunks at a few MiB (rosbag: 768 kB, rosbag2's MCAP: 4 MiB).
inline constexpr std::uint64_t kMaxChunkBytes = 256ull << 20;
// The uncompressed chunks a reader keeps for the messages that follow (topics recorded with
// different delays interleave neighbouring chunks in time): at most this many bytes together.
inline constexpr std::uint64_t kMaxCachedChunkBytes = 256ull << 20;

// The chunks read last, uncompressed, held within a budget of bytes and of chunks (a lookup walks
// them); the least recently used go first. A reference returned stays valid until the next insert.
class ChunkCache {
 public:
  explicit ChunkCache(std::size_t max_chunks, std::uint64_t max_bytes = kMaxCachedChunkBytes)
      : max_chunks_(max_chunks), max_bytes_(max_bytes) {}

  // Chunk `k`'s bytes if they are held (and marks them used), else null.
  const std::string* find(std::uint32_t k);
  // Lets the least recently used chunks go until a chunk of `bytes` fits beside the rest: called
  // before decompressing one, so that the old and the new are never held together past the budget.
  void makeRoom(std::uint64_t bytes);
  // Holds chunk `k`'s bytes, letting the least recently used chunks go until all fit the budget
  // (the new chunk is always held, alone if it must be).
  const std::string& insert(std::uint32_t k, std::string bytes);

  std::uint64_t heldBytes() const { return held_bytes_; }
  std::size_t heldChunks() const { return chunks_.size(); }

 private:
  struct Held {
    std::uint32_t chunk = 0;
    std::uint64_t used = 0;
    std::string bytes;
  };
  std::size_t max_chunks_;
  std::uint64_t max_bytes_;
  std::uint64_t held_bytes_ = 0;
  std::uint64_t uses_ = 0;
  std::vector<Held> chunks_;
};

}  // namespace isg::formats
