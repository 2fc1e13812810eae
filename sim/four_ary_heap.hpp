#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace isg::sim {

// A min-heap of (key, value) pairs with four children per node, ordered by the pair (key first,
// then value). Why not std::priority_queue: A* on a large floor's grid pops millions of entries,
// and a pop walks the heap down to a leaf: with four children per node that walk has half the
// levels, and a node's children share a cache line. Distinct pairs pop in the same order from any
// correct heap, so a search that used std::priority_queue expands the same cells in the same order
// with this one (the A* pushes each (f, cell) pair at most once).
class FourAryHeap {
 public:
  using Entry = std::pair<double, int>;

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  const Entry& top() const { return entries_.front(); }
  void clear() { entries_.clear(); }

  void push(const Entry& entry) {
    std::size_t at = entries_.size();
    entries_.push_back(entry);
    while (at > 0) {
      const std::size_t parent = (at - 1) / 4;
      if (!(entry < entries_[parent])) break;
      entries_[at] = entries_[parent];
      at = parent;
    }
    entries_[at] = entry;
  }

  void pop() {
    const Entry last = entries_.back();
    entries_.pop_back();
    const std::size_t n = entries_.size();
    if (n == 0) return;
    std::size_t at = 0;
    while (true) {
      const std::size_t first = 4 * at + 1;
      if (first >= n) break;
      std::size_t least = first;
      const std::size_t end = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < end; ++c) {
        if (entries_[c] < entries_[least]) least = c;
      }
      if (!(entries_[least] < last)) break;
      entries_[at] = entries_[least];
      at = least;
    }
    entries_[at] = last;
  }

 private:
  std::vector<Entry> entries_;
};

}  // namespace isg::sim
