# fmt, nlohmann-json, toml++ and CLI11 as header-only libraries, from the headers of the Debian -dev packages,
# for a cross build (cmake/mingw-w64.cmake) that has no Windows builds of them. Only those four folders are put on
# the include path, through links in the build folder: /usr/include itself holds glibc's headers, which must never
# shadow the target's.
set(RRFLINT_DEPS_INCLUDE ${CMAKE_CURRENT_BINARY_DIR}/header-only-deps)
file(MAKE_DIRECTORY ${RRFLINT_DEPS_INCLUDE})
foreach(dir fmt nlohmann CLI toml++)
  if(NOT IS_DIRECTORY /usr/include/${dir})
    message(FATAL_ERROR "/usr/include/${dir} is missing (scripts/setup.sh installs the -dev packages)")
  endif()
  file(CREATE_LINK /usr/include/${dir} ${RRFLINT_DEPS_INCLUDE}/${dir} SYMBOLIC)
endforeach()
add_library(rrflint_header_only_deps INTERFACE)
target_include_directories(rrflint_header_only_deps SYSTEM INTERFACE ${RRFLINT_DEPS_INCLUDE})
target_compile_definitions(rrflint_header_only_deps INTERFACE FMT_HEADER_ONLY TOML_HEADER_ONLY=1)
foreach(target fmt::fmt nlohmann_json::nlohmann_json CLI11::CLI11 tomlplusplus::tomlplusplus)
  add_library(${target} ALIAS rrflint_header_only_deps)
endforeach()
