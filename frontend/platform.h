// The one place where rrflint's POSIX calls meet Windows (the MinGW-w64 cross build, cmake/mingw-w64.cmake).
// On POSIX systems this header only includes the system headers and defines file_mtime_ns and replace_file; on
// Windows it supplies what the MSVC runtime lacks or names differently, with the meaning rrflint needs:
//   - open() flags that do not exist there are 0, and every file is opened in binary mode (O_BINARY: no CRLF
//     translation, which would hide the CR line endings rules look for);
//   - there are no symbolic links, sockets or owners to keep: S_ISLNK/S_ISSOCK are false, fchown and fchmod do
//     nothing (a file is writable or read-only, and the temporary file is created writable), geteuid is not root;
//   - mkstemp creates the file exclusively; fsync is _commit; replace_file renames over an existing file.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <cstdint>
#include <cstdio>

#ifdef _WIN32
#include <io.h>
#include <process.h>
#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif
#ifndef O_NONBLOCK
#define O_NONBLOCK 0
#endif
#ifndef O_NOCTTY
#define O_NOCTTY 0
#endif
#undef O_RDONLY
#define O_RDONLY (_O_RDONLY | _O_BINARY)
#ifndef S_ISLNK
#define S_ISLNK(m) false
#endif
#ifndef S_ISSOCK
#define S_ISSOCK(m) false
#endif
#ifndef W_OK
#define W_OK 2
#endif
#ifndef ELOOP
#define ELOOP 114
#endif

// _pclose returns the exit code itself.
#define WIFEXITED(status) ((status) != -1)
#define WEXITSTATUS(status) (status)

inline int fsync(int fd) { return _commit(fd); }
inline int lstat(const char* path, struct stat* st) { return stat(path, st); }
inline int fchmod(int, unsigned) { return 0; }
inline int fchown(int, short, short) { return 0; }
inline int geteuid() { return 1; }
inline int mkstemp(char* tmpl) {
  if (_mktemp_s(tmpl, std::strlen(tmpl) + 1) != 0) return -1;
  return _open(tmpl, _O_CREAT | _O_EXCL | _O_RDWR | _O_BINARY, _S_IREAD | _S_IWRITE);
}
#else
#include <unistd.h>
#endif

namespace rrflint {

/// The modification time of a stat result, in nanoseconds where the system has them.
inline int64_t file_mtime_ns(const struct stat& st) {
#ifdef _WIN32
  return int64_t{st.st_mtime} * 1'000'000'000;
#else
  return int64_t{st.st_mtim.tv_sec} * 1'000'000'000 + st.st_mtim.tv_nsec;
#endif
}

/// Waits up to `timeout_ms` for input on `fd` (poll() on POSIX): 1 when there is some (or the end of it, or an
/// error a read will report), 0 when the time ran out, -1 with errno set when the wait failed. On Windows a pipe is
/// polled with PeekNamedPipe every millisecond; any other kind of handle (a file, the console) reads as ready, so
/// the caller's read blocks, as before a debounce existed.
int wait_readable(int fd, int timeout_ms);

/// Renames `from` over `to` (which may exist) in one step; 0 or -1 with errno set.
inline int replace_file(const char* from, const char* to) {
#ifdef _WIN32
  std::error_code ec;  // libstdc++: MoveFileExW with MOVEFILE_REPLACE_EXISTING
  std::filesystem::rename(from, to, ec);
  if (!ec) return 0;
  errno = ec.value() ? EACCES : 0;
  return -1;
#else
  return std::rename(from, to);
#endif
}

}  // namespace rrflint
