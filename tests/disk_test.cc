// The disk layer: opening, probing and reading files; large files mapped instead of copied.
#include <string>

#include <catch2/catch.hpp>

#include "frontend/disk.h"
#include "tests/cli_util.h"

using namespace rrflint;

TEST_CASE("disk: probe_file says what read_file would say, and reads nothing", "[disk]") {
  test::TempTree t;
  const std::string file = t.write("sys/config.g", "M83\n").string();
  std::string err;
  CHECK(probe_file(file, &err));
  CHECK_FALSE(probe_file((t / "sys/none.g").string(), &err));
  CHECK(err == "no such file");
  CHECK_FALSE(read_file((t / "sys/none.g").string(), &err));
  CHECK(err == "no such file");
  CHECK_FALSE(probe_file((t / "sys").string(), &err));
  CHECK(err == "is a directory");
  CHECK_FALSE(read_file((t / "sys").string(), &err));
  CHECK(err == "is a directory");
}

TEST_CASE("disk: read_text maps a large file only when asked to, with the same bytes", "[disk]") {
  test::TempTree t;
  std::string big;
  while (big.size() < (size_t{4} << 20)) big += "G1 X10.5 Y20 F3000 ; a move\n";
  big.resize(size_t{4} << 20);  // a whole number of pages: a scan must not read past the mapping
  const std::string path = t.write("big.g", big).string();
  const std::string small = t.write("small.g", "M83\n").string();
  std::string err;
  for (bool on : {false, true}) {
    INFO("mapping " << on);
    map_large_files(on);
    auto b = read_text(path, &err);
    REQUIRE(b);
    CHECK(b->is_mapped() == on);
    CHECK(std::string_view(*b) == big);
    auto s = read_text(small, &err);
    REQUIRE(s);
    CHECK_FALSE(s->is_mapped());  // small files are read
    CHECK(std::string_view(*s) == "M83\n");
    // A copy shares the mapping and outlives the original.
    TextBuffer copy;
    {
      TextBuffer first = std::move(*b);
      copy = first;
    }
    CHECK(std::string_view(copy) == big);
    // The line index and the parse see the same file either way.
    const SourceFile f(0, "big.g", "/sys/big.g", copy, 2);
    CHECK(f.line_count() == 149797);
    CHECK_FALSE(f.any_nul());
  }
  map_large_files(false);
  CHECK_FALSE(read_text((t / "none.g").string(), &err));
  CHECK(err == "no such file");
}
