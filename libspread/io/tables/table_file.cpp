#include "libspread/io/tables/table_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables::detail {
namespace {

bool non_empty_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

std::int32_t big_endian_int32(const unsigned char* bytes) {
  return static_cast<std::int32_t>((std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) |
                                   (std::uint32_t{bytes[2]} << 8) | std::uint32_t{bytes[3]});
}

}  // namespace

TableFileInfo inspect_table_file(const std::string& path, bool allow_missing) {
  TableFileInfo info;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) {
      if (allow_missing) return info;
      throw TableError(TableErrorKind::kMissing, path + ": no such file");
    }
    throw TableError(TableErrorKind::kIo, path + ": cannot look at the file: " + std::strerror(error));
  }
  info.exists = true;
  if (S_ISDIR(st.st_mode)) throw TableError(TableErrorKind::kNotOurs, path + ": is a directory, not a table file");
  if (!S_ISREG(st.st_mode)) {
    throw TableError(TableErrorKind::kNotOurs,
                     path + ": not a regular file (a FIFO, socket or device); a table file is a regular file");
  }
  // O_NONBLOCK: should the path have become a FIFO since stat(), the open returns instead of waiting.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    throw TableError(TableErrorKind::kIo, path + ": cannot read the file: " + std::strerror(errno));
  }
  unsigned char header[100] = {};
  const ssize_t got = ::read(fd, header, sizeof header);
  ::close(fd);
  info.empty = st.st_size == 0;
  info.bytes = static_cast<std::int64_t>(st.st_size);
  if (got == static_cast<ssize_t>(sizeof header)) {
    info.sqlite = std::memcmp(header, "SQLite format 3", 16) == 0;
    info.wal = info.sqlite && header[18] == 2 && header[19] == 2;
    info.application_id = big_endian_int32(header + 68);
    info.user_version = big_endian_int32(header + 60);
  }
  info.wal_has_content = non_empty_file(path + "-wal");
  info.hot_journal = non_empty_file(path + "-journal");
  return info;
}

}  // namespace spread::tables::detail
