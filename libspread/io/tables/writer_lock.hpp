#pragma once
// The writer lock of a table file: an exclusive flock(2) on the file itself, held while a writer lives.
// flock locks are independent of the POSIX record locks SQLite takes, and the kernel drops them when the
// process dies, so a killed writer never leaves a stale lock. TableWriter takes it on the file it writes;
// lookup_builder takes it on the table it will replace as well, so two builds never interleave.
#include <string>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

// Another process holds the file's writer lock: two writers never interleave their runs. The message
// names the holder's pid.
class TableBusyError : public TableError {
 public:
  using TableError::TableError;
};

class WriterLock {
 public:
  // Opens (creating an empty file if there is none) and locks `path`; TableBusyError when another
  // process holds the lock, TableError kIo when the file cannot be opened or locked.
  explicit WriterLock(const std::string& path);
  ~WriterLock();
  WriterLock(const WriterLock&) = delete;
  WriterLock& operator=(const WriterLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace spread::tables
