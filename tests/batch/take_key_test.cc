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
  take.options = {{"filter_levels", number}};
  TakeKey key;
  ASSERT_TRUE(ComputeTakeKey(take, "1.0", &key).ok());
  ASSERT_EQ(key.inputs.size(), 3u);  // The subject's skeleton file counts.
  EXPECT_EQ(key.inputs[2].role, "skeleton");

  BatchTake moved = take;  // Same contents elsewhere: the same key.
  moved.markers = dir + "/b/take.c3d";
  moved.subject = dir + "/b/S.json";
  TakeKey other;
  ASSERT_TRUE(ComputeTakeKey(moved, "1.0", &other).ok());
  EXPECT_EQ(other.key, key.key);

  ASSERT_TRUE(ComputeTakeKey(take, "1.1", &other).ok());
  EXPECT_NE(other.key, key.key);
  BatchTake changed = take;
  changed.options[0].second.number = 2;
  ASSERT_TRUE(ComputeTakeKey(changed, "1.0", &other).ok());
  EXPECT_NE(other.key, key.key);
  testing::WriteTextFile(dir + "/b/skeleton.bvh", "skeleton2");
  ASSERT_TRUE(ComputeTakeKey(moved, "1.0", &other).ok());
  EXPECT_NE(other.key, key.key);
}

}  // namespace
}  // namespace mocapsolve
