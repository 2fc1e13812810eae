#include "slam/thread_pool.hpp"

namespace isg::slam {

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { work(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void ThreadPool::drain(std::unique_lock<std::mutex>& lock) {
  while (task_ != nullptr && next_ < items_) {
    const int item = next_++;
    const auto* task = task_;
    lock.unlock();
    (*task)(item);
    lock.lock();
    if (++done_ == items_) finished_.notify_all();
  }
}

void ThreadPool::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [&] { return stop_ || (task_ != nullptr && next_ < items_); });
    if (stop_) return;
    drain(lock);
  }
}

void ThreadPool::run(int n, const std::function<void(int)>& task) {
  if (n <= 0) return;
  if (workers_.empty() || n == 1) {
    for (int i = 0; i < n; ++i) task(i);
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  task_ = &task;
  items_ = n;
  next_ = 0;
  done_ = 0;
  wake_.notify_all();
  drain(lock);
  finished_.wait(lock, [&] { return done_ == items_; });
  task_ = nullptr;
}

}  // namespace isg::slam
