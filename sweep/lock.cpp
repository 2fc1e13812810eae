#include "sweep/lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "common/input_error.hpp"
#include "sweep/suite.hpp"

namespace isg::sweep {

SweepLock::SweepLock(const std::string& sweep_dir) {
  const std::string path = (std::filesystem::path(sweep_dir) / kSweepLockFile).string();
  // Never through a symlink: the pid written below would truncate whatever it points to.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0) {
    throw common::InputError(path, "",
                             std::string("cannot open the sweep's lock: ") + std::strerror(errno));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char holder[32] = {};
    const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (error != EWOULDBLOCK) {
      throw common::InputError(path, "", std::string("cannot lock: ") + std::strerror(error));
    }
    std::string pid = n > 0 ? std::string(holder, std::size_t(n)) : "";
    while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
    throw common::InputError(sweep_dir, "",
                             "another isg sweep is running in this folder (pid " +
                                 (pid.empty() ? std::string("unknown") : pid) +
                                 "); wait for it to end, or stop it, then run this again");
  }
  // The holder's pid, for the message above; the file itself stays (removing it would let two
  // processes lock two different files of one name).
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The lock holds without the pid; only the message of a refused sweep is poorer.
  }
}

SweepLock::~SweepLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace isg::sweep
