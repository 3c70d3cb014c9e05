// The parts of platform.h that need the system's own headers (<windows.h> stays out of the header).
#include "frontend/platform.h"

#ifdef _WIN32
#include "frontend/win32.h"
#else
#include <poll.h>
#endif

namespace rrflint {

int wait_readable(int fd, int timeout_ms) {
#ifdef _WIN32
  HANDLE h = reinterpret_cast<HANDLE>(_get_osfhandle(fd));
  if (h == INVALID_HANDLE_VALUE || GetFileType(h) != FILE_TYPE_PIPE) return 1;
  const ULONGLONG until = GetTickCount64() + static_cast<ULONGLONG>(timeout_ms < 0 ? 0 : timeout_ms);
  for (;;) {
    DWORD avail = 0;
    if (!PeekNamedPipe(h, nullptr, 0, nullptr, &avail, nullptr) || avail > 0) return 1;
    if (GetTickCount64() >= until) return 0;
    Sleep(1);
  }
#else
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms);
#endif
}

}  // namespace rrflint
