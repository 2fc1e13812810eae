#include "formats/chunk_cache.hpp"

#include <algorithm>

namespace isg::formats {

const std::string* ChunkCache::find(std::uint32_t k) {
  for (Held& held : chunks_) {
    if (held.chunk == k) {
      held.used = ++uses_;
      return &held.bytes;
    }
  }
  return nullptr;
}

void ChunkCache::makeRoom(std::uint64_t bytes) {
  while (!chunks_.empty() && (chunks_.size() >= max_chunks_ || held_bytes_ + bytes > max_bytes_)) {
    const auto oldest =
        std::min_element(chunks_.begin(), chunks_.end(),
                         [](const Held& a, const Held& b) { return a.used < b.used; });
    held_bytes_ -= oldest->bytes.size();
    chunks_.erase(oldest);
  }
}

const std::string& ChunkCache::insert(std::uint32_t k, std::string bytes) {
  makeRoom(bytes.size());
  held_bytes_ += bytes.size();
  chunks_.push_back({k, ++uses_, std::move(bytes)});
  return chunks_.back().bytes;
}

}  // namespace isg::formats
