// Take keys: FNV-1a 64 against its published test vectors, and a key that changes with
// each input's contents, the options and the version, but not with the files' paths.
#include "batch/take_key.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {


TEST(Fnv1a64, PublishedVectors) {
  // Fowler/Noll/Vo test vectors (64-bit FNV-1a).
  Fnv1a64 empty;
  EXPECT_EQ(HexHash(empty.value()), "cbf29ce484222325");
  Fnv1a64 a;
  a.Update("a");
  EXPECT_EQ(HexHash(a.value()), "af63dc4c8601ec8c");
  Fnv1a64 foobar;
  foobar.Update("foo");
  foobar.Update("bar");  // Incremental = one piece.
  EXPECT_EQ(HexHash(foobar.value()), "85944171f73967e8");
}

TEST(HashFile, MatchesTheBytesAndNamesAMissingFile) {
  const std::string path = testing::TempPath("bytes.bin");
  testing::WriteTextFile(path, "foobar");
  uint64_t hash = 0;
  ASSERT_TRUE(HashFile(path, &hash).ok());
  EXPECT_EQ(HexHash(hash), "85944171f73967e8");
  const Status status = HashFile(testing::TempPath("missing.bin"), &hash);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("missing.bin"), std::string::npos) << status.message();
}

TEST(TakeKey, ChangesWithContentsOptionsAndVersionOnly) {
  const std::string dir = testing::TempPath("key");
  ASSERT_EQ(std::system(("mkdir -p " + dir + "/a " + dir + "/b").c_str()), 0);
  for (const std::string& folder : {dir + "/a/", dir + "/b/"}) {
    testing::WriteTextFile(folder + "take.c3d", "markers");
    testing::WriteTextFile(folder + "skeleton.bvh", "skeleton");
    testing::WriteTextFile(folder + "S.json", "{\"skeleton\": \"skeleton.bvh\"}");
  }
  BatchTake take;
  take.markers = dir + "/a/take.c3d";
  take.subject = dir + "/a/S.json";
  JsonNode number;
  number.type = JsonNode::Type::kNumber;
  number.number = 1;
  BatchManifest manifest;
  manifest.pipeline = {{"filter_levels", number}};
  TakeKey key;
  ASSERT_TRUE(ComputeTakeKey(manifest, take, "1.0", &key).ok());
  ASSERT_EQ(key.inputs.size(), 3u);  // The subject's skeleton file counts.
  EXPECT_EQ(key.inputs[2].role, "skeleton");

  BatchTake moved = take;  // Same contents elsewhere: the same key.
  moved.markers = dir + "/b/take.c3d";
  moved.subject = dir + "/b/S.json";
  TakeKey other;
  ASSERT_TRUE(ComputeTakeKey(manifest, moved, "1.0", &other).ok());
  EXPECT_EQ(other.key, key.key);

  ASSERT_TRUE(ComputeTakeKey(manifest, take, "1.1", &other).ok());
  EXPECT_NE(other.key, key.key);
  BatchTake changed = take;
  number.number = 2;
  changed.overrides = {{"filter_levels", number}};
  ASSERT_TRUE(ComputeTakeKey(manifest, changed, "1.0", &other).ok());
  EXPECT_NE(other.key, key.key);
  testing::WriteTextFile(dir + "/b/skeleton.bvh", "skeleton2");
  ASSERT_TRUE(ComputeTakeKey(manifest, moved, "1.0", &other).ok());
  EXPECT_NE(other.key, key.key);
}

// Inputs that are not regular files fail the key at once (no read blocks on a FIFO), with
// the role and path named; the cache does not hide a take's own markers file.
TEST(TakeKey, RefusesFifosFoldersAndMissingFilesWithoutBlocking) {
  const std::string dir = testing::TempPath("key_fifo");
  ASSERT_EQ(std::system(("mkdir -p " + dir + "/folder.c3d && rm -f " + dir + "/fifo.c3d && mkfifo " + dir +
                         "/fifo.c3d").c_str()), 0);
  testing::WriteTextFile(dir + "/S.json", "{}");
  testing::WriteTextFile(dir + "/ok.c3d", "x");
  BatchManifest manifest;
  TakeKeyCache cache;
  BatchTake take;
  take.subject = dir + "/S.json";
  take.markers = dir + "/ok.c3d";
  TakeKey key;
  ASSERT_TRUE(ComputeTakeKey(manifest, take, "1.0", &key, &cache).ok());
  for (const char* name : {"fifo.c3d", "folder.c3d", "missing.c3d"}) {
    take.markers = dir + "/" + name;
    const Status status = ComputeTakeKey(manifest, take, "1.0", &key, &cache);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_NE(status.message().find(std::string("markers: ") + dir + "/" + name), std::string::npos)
        << status.message();
  }
  take.markers = dir + "/ok.c3d";
  take.subject = dir + "/fifo.c3d";  // A FIFO subject: its skeleton is looked for too.
  const Status status = ComputeTakeKey(manifest, take, "1.0", &key, &cache);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("is not a regular file (a FIFO)"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
