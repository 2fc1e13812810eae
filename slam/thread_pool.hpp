#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace isg::slam {

// A few threads for the localizer's own loops (the local map's normals, the registration's
// correspondences). run(n, task) calls task(i) once for each i in [0, n), the calling thread
// taking part, and returns when all are done. Which thread runs an item never changes what the
// item computes: callers split work into items that do not depend on the number of threads and
// combine the items' results in item order, so results are the same with 1 thread or 8. Tasks
// must not throw.
class ThreadPool {
 public:
  explicit ThreadPool(int threads);  // threads in all, the caller's included; ≤ 1: none started
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return int(workers_.size()) + 1; }
  void run(int n, const std::function<void(int)>& task);

 private:
  void work();
  // Takes items of the current batch until none is left; called with `lock` held.
  void drain(std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  const std::function<void(int)>* task_ = nullptr;
  int items_ = 0, next_ = 0, done_ = 0;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

// Items of at most `size` elements over `count` elements: item i covers
// [i · size, min(count, (i + 1) · size)).
inline int itemCount(int count, int size) { return (count + size - 1) / size; }

}  // namespace isg::slam
