// <windows.h> for the few Windows-only pieces (cli/main.cc: the console; cli/docs_url.cc: the binary's path),
// without its min/max macros and the rarely used parts. Include it only inside #ifdef _WIN32.
#pragma once

#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>
