# Cross-compiling rrflint.exe for 64-bit Windows with Debian's MinGW-w64 (g++-mingw-w64-x86-64-posix: the
# POSIX thread model, which std::thread needs). scripts/windows.sh uses it:
#   cmake -S . -B build-windows -DCMAKE_TOOLCHAIN_FILE=cmake/mingw-w64.cmake
# The libraries are used header-only from the Debian -dev packages (cmake/header-only-deps.cmake), and the C++
# runtime, libgcc and winpthread are linked statically, so rrflint.exe runs alone.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_STRIP x86_64-w64-mingw32-strip)  # cmake --install --strip (scripts/windows.sh): the zip without debug symbols
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(RRFLINT_HEADER_ONLY_DEPS ON CACHE BOOL "fmt, nlohmann-json, toml++ and CLI11 header-only from /usr/include")
# The zip's layout: rrflint.exe at its top, the rule pages in docs/ beside it (cli/docs_url.cc finds them there).
set(CMAKE_INSTALL_BINDIR "." CACHE PATH "")
set(CMAKE_INSTALL_DOCDIR "docs" CACHE PATH "")
