#pragma once

#include <string>

namespace isg::sweep {

// The lock a sweep holds on its folder while it runs (SWEEP_DIR/.lock, an flock): a second
// `isg sweep` into the same folder is refused with an InputError naming the holder's pid, rather
// than running every cell twice. The kernel drops the lock when the holder ends, however it ends.
class SweepLock {
 public:
  explicit SweepLock(const std::string& sweep_dir);
  ~SweepLock();
  SweepLock(const SweepLock&) = delete;
  SweepLock& operator=(const SweepLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace isg::sweep
