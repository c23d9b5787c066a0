// .pk3 archives: entries by name (any case), and clear errors for missing or broken archives.
#include <gtest/gtest.h>

#include "bounce/scene/quake/pk3.h"
#include "bsp_build.h"
#include "scene_test_util.h"

namespace bounce::scene_test {
namespace {

using quake::Pk3Archive;

TEST(Pk3, ReadsEntriesByNameInAnyCase) {
  TempDir dir;
  const std::string path =
      dir.write("a.pk3", stored_zip({{"maps/Room.bsp", "IBSP-bytes"}, {"scripts/x.shader", "y"}}));
  const Pk3Archive a(path);
  EXPECT_EQ(a.names().size(), 2u);
  EXPECT_TRUE(a.contains("MAPS/room.BSP"));
  const auto bytes = a.read("maps/room.bsp");
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "IBSP-bytes");
}

TEST(Pk3, MissingArchiveAndEntry) {
  TempDir dir;
  std::string e = error_of([&] { Pk3Archive(dir.file("none.pk3")); });
  EXPECT_TRUE(contains(e, "none.pk3") && contains(e, "not found")) << e;
  const Pk3Archive a(dir.write("a.pk3", stored_zip({{"x.txt", "x"}})));
  e = error_of([&] { a.read("maps/gone.bsp"); });
  EXPECT_TRUE(contains(e, "a.pk3") && contains(e, "no entry 'maps/gone.bsp'")) << e;
}

// A device or a directory named as an archive is refused before libzip reads from it.
TEST(Pk3, OnlyRegularFilesAreArchives) {
  TempDir dir;
  for (const std::string& path : {std::string("/dev/zero"), dir.file("")}) {
    const std::string e = error_of([&] { Pk3Archive a(path); });
    EXPECT_TRUE(contains(e, "not a regular file")) << e;
  }
}

TEST(Pk3, NotAZipIsAnError) {
  TempDir dir;
  const std::string e = error_of([&] { Pk3Archive(dir.write("junk.pk3", std::string(300, 'q'))); });
  EXPECT_TRUE(contains(e, "junk.pk3") && contains(e, "not a readable .pk3")) << e;
}

TEST(Pk3, CorruptEntryDataFailsItsChecksum) {
  TempDir dir;
  std::string zip = stored_zip({{"maps/a.bsp", std::string(1000, 'a')}});
  zip[30 + 10 + 500] = 'b';  // a byte of the stored data, after the 30-byte header and the name
  const Pk3Archive a(dir.write("bad.pk3", zip));
  const std::string e = error_of([&] { a.read("maps/a.bsp"); });
  EXPECT_TRUE(contains(e, "bad.pk3") && contains(e, "maps/a.bsp") && contains(e, "corrupt")) << e;
}

TEST(Pk3, TruncatedArchiveIsAnError) {
  TempDir dir;
  const std::string zip = stored_zip({{"maps/a.bsp", std::string(1000, 'a')}});
  const std::string e =
      error_of([&] { Pk3Archive(dir.write("cut.pk3", zip.substr(0, zip.size() - 30))); });
  EXPECT_TRUE(contains(e, "cut.pk3")) << e;
}

}  // namespace
}  // namespace bounce::scene_test
