#include "libspread/io/tables/writer_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace spread::tables {

namespace {

// The pid holding a flock(2) on the inode, from /proc/locks ("1: FLOCK  ADVISORY  WRITE 4242 08:01:1234 0 EOF");
// 0 when it cannot be told.
long flock_holder_pid(ino_t inode) {
  std::ifstream locks("/proc/locks");
  std::string line;
  while (std::getline(locks, line)) {
    std::istringstream fields(line);
    std::string number, type, advisory, access, device;
    long pid = 0;
    if (!(fields >> number >> type)) continue;
    if (type == "->") fields >> type;  // a waiter's line
    if (type != "FLOCK" || !(fields >> advisory >> access >> pid >> device)) continue;
    const std::size_t colon = device.rfind(':');
    if (colon != std::string::npos && device.substr(colon + 1) == std::to_string(inode)) return pid;
  }
  return 0;
}

}  // namespace

WriterLock::WriterLock(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) throw TableError(TableErrorKind::kIo, path + ": cannot open for writing: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    struct stat st {};
    const long pid = ::fstat(fd_, &st) == 0 ? flock_holder_pid(st.st_ino) : 0;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw TableBusyError(TableErrorKind::kIo, path + ": another writer (" +
                                                    (pid > 0 ? "pid " + std::to_string(pid) : std::string("pid unknown")) +
                                                    ") is writing this table file; wait for it to finish");
    }
    throw TableError(TableErrorKind::kIo, path + ": cannot lock for writing: " + std::strerror(error));
  }
}

WriterLock::~WriterLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace spread::tables
