// Issue 15, held-out robustness: malformed variants of the project's own small good file of
// every format (tests/data/good, written by fuzz/make_seeds.py, plus a subject made for
// this test), each run through the command that reads that format, as a user would run it.
//
// Variants of a file of n bytes (seeded, so a failure is reproducible):
//   - truncated at 1, 7, n/8, 2n/8, ..., 7n/8 and n-1 bytes, and empty;
//   - 1 to 3 bytes overwritten near the start (header fields, counts, magic) or anywhere;
//   - text formats: one number replaced by nan, inf, -inf, 1e309, -1e308, 2147483648,
//     a 20-digit integer or -1; and two random edits (test_support's RandomlyDamaged);
//   - binary formats (C3D, GLB): a 4-byte float NaN, inf, -FLT_MAX or 1e38 written at a
//     random aligned offset;
//   - a directory where the file should be, and a path that does not exist.
// For each: no signal, exit code 0 (the variant happens to be valid) or 1, and with 1
// exactly one line of output naming the variant, no file (not even a temporary one) left in
// the output folder; within 5 s. The held-out corpus of the issue is checked the same way.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// One good file and the commands that read it. In a command, IN is the variant's path, OUT
// a fresh output folder and DIR the folder holding the companion good files.
struct Fixture {
  const char* name;
  const char* file;  // Under tests/data/good.
  bool binary;
  const char* command;
  const char* info;  // A second command for every other variant ("" = none).
};

const Fixture kFixtures[] = {
    {"bvh", "small.bvh", false, "convert IN OUT/x.bvh", "info IN"},
    {"asf", "small.asf", false, "convert DIR/small.amc OUT/x.bvh --skeleton=IN", "info DIR/small.amc --skeleton=IN"},
    {"amc", "small.amc", false, "convert IN OUT/x.bvh --skeleton=DIR/small.asf", "info IN --skeleton=DIR/small.asf"},
    {"c3d", "small.c3d", true, "convert IN OUT/x.trc", "info IN"},
    {"trc", "small.trc", false, "convert IN OUT/x.c3d", "info IN"},
    {"gltf", "skinned.gltf", false, "convert IN OUT/x.bvh", "info IN"},
    {"glb", "skinned.glb", true, "convert IN OUT/x.bvh", "info IN"},
    {"fbx", "small.fbx", false, "convert IN OUT/x.bvh", "info IN"},
    {"markerset", "markerset.json", false,
     "markers --quiet --motion=DIR/small.bvh --markerset=IN --out=OUT/x.c3d", ""},
    {"edit", "edit.json", false, "propagate --quiet --motion=DIR/small.bvh --frame=0 --edit=IN --out=OUT/x.bvh",
     ""},
    {"subject", "subject.json", false,
     "solve --quiet --solver=dls --subject=IN --markers=DIR/small.c3d --out=OUT/x.bvh", ""},
};

struct Variant {
  std::string label;  // Goes into the file name.
  std::string bytes;
  bool directory = false;
  bool missing = false;
};

std::vector<Variant> MakeVariants(const std::string& good, bool binary, std::mt19937* rng) {
  std::vector<Variant> variants;
  const size_t n = good.size();
  std::vector<size_t> cuts = {1, 7, n - 1};
  for (size_t k = 1; k < 8; ++k) cuts.push_back(n * k / 8);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  for (size_t cut : cuts) {
    if (cut > 0 && cut < n) variants.push_back({"cut" + std::to_string(cut), good.substr(0, cut)});
  }
  variants.push_back({"empty", ""});
  const char kBytes[] = {'\0', '\xff', '\x7f', '\x80', '9', '-', '{', '\n'};
  for (int k = 0; k < 6; ++k) {
    // Half near the start (magic, header counts), half anywhere in the first KB.
    const size_t span = std::min(n, k % 2 == 0 ? size_t{32} : size_t{1024});
    std::string bytes = good;
    const int edits = 1 + static_cast<int>((*rng)() % 3);
    for (int e = 0; e < edits; ++e) bytes[(*rng)() % span] = kBytes[(*rng)() % sizeof kBytes];
    variants.push_back({"flip" + std::to_string(k), bytes});
  }
  if (binary) {
    const float kFloats[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::max(), 1e38f};
    for (int k = 0; k < 4; ++k) {
      std::string bytes = good;
      const size_t at = ((*rng)() % (n / 4)) * 4;
      std::memcpy(&bytes[at], &kFloats[k], 4);
      variants.push_back({"float" + std::to_string(k), bytes});
    }
  } else {
    static const std::regex kNumber("[-+]?[0-9]*\\.?[0-9]+([eE][-+]?[0-9]+)?");
    std::vector<std::pair<size_t, size_t>> numbers;  // (offset, length)
    for (auto it = std::sregex_iterator(good.begin(), good.end(), kNumber); it != std::sregex_iterator(); ++it) {
      numbers.emplace_back(it->position(), it->length());
    }
    const char* kValues[] = {"nan", "inf", "-inf", "1e309", "-1e308", "2147483648", "99999999999999999999", "-1"};
    for (size_t k = 0; k < std::size(kValues) && !numbers.empty(); ++k) {
      const auto [at, length] = numbers[(*rng)() % numbers.size()];
      variants.push_back({"number" + std::to_string(k), good.substr(0, at) + kValues[k] + good.substr(at + length)});
    }
    const std::string alphabet = "0123456789.-e \n\t{}[]\":,abcXYZ";
    for (int k = 0; k < 2; ++k) {
      variants.push_back({"damaged" + std::to_string(k), testing::RandomlyDamaged(good, alphabet, rng)});
    }
  }
  variants.push_back({"directory", "", true, false});
  variants.push_back({"missing", "", false, true});
  return variants;
}

std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

bool EmptyFolder(const std::string& path, std::string* listing) {
  listing->clear();
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    *listing += entry.path().filename().string() + " ";
  }
  return listing->empty();
}

class MalformedInputSweep : public ::testing::TestWithParam<Fixture> {};

TEST_P(MalformedInputSweep, OneLineErrorOrSuccessNeverACrash) {
  const Fixture& fixture = GetParam();
  const std::string good_dir = testing::SourcePath("tests/data/good");
  const std::string good = testing::ReadTextFile(good_dir + "/" + fixture.file);
  ASSERT_GT(good.size(), 16u) << fixture.file;
  // The companions (the skeleton of an AMC, the motion of a marker set, ...) sit beside
  // the variants, so that a subject's relative skeleton path resolves.
  const std::string dir = testing::TempPath("");
  for (const char* companion : {"small.bvh", "small.asf", "small.amc", "small.c3d"}) {
    testing::WriteTextFile(dir + companion, testing::ReadTextFile(good_dir + "/" + companion));
  }
  const std::string stem = std::filesystem::path(fixture.file).stem().string();
  const std::string extension = std::filesystem::path(fixture.file).extension().string();
  const std::string cli = std::string("timeout -s KILL 60 ") + testing::CliPath();

  // The good file itself must pass, or the sweep tests nothing.
  {
    const std::string out = dir + "out_good";
    std::filesystem::create_directory(out);
    std::string output;
    const std::string command = Replaced(Replaced(Replaced(fixture.command, "IN", good_dir + "/" + fixture.file),
                                                  "OUT", out), "DIR", dir.substr(0, dir.size() - 1));
    ASSERT_EQ(testing::RunProgram(cli, command, &output), 0) << command << "\n" << output;
  }

  std::mt19937 rng(15);
  const std::vector<Variant> variants = MakeVariants(good, fixture.binary, &rng);
  int refused = 0, accepted = 0;
  for (size_t v = 0; v < variants.size(); ++v) {
    const Variant& variant = variants[v];
    const std::string name = stem + "_" + variant.label + extension;
    const std::string path = dir + name;
    if (variant.directory) {
      std::filesystem::create_directory(path);
    } else if (!variant.missing) {
      testing::WriteTextFile(path, variant.bytes);
    }
    const std::string out = dir + "out_" + variant.label;
    std::filesystem::create_directory(out);
    const std::string pattern = (v % 2 == 1 && *fixture.info) ? fixture.info : fixture.command;
    const std::string command =
        Replaced(Replaced(Replaced(pattern, "IN", path), "OUT", out), "DIR", dir.substr(0, dir.size() - 1));
    std::string output;
    const auto start = std::chrono::steady_clock::now();
    const int code = testing::RunProgram(cli, command, &output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    SCOPED_TRACE(command + "\n" + output);
    EXPECT_TRUE(code == 0 || code == 1) << name << ": exit code " << code;
    EXPECT_LT(seconds, 5.0) << name;
    if (code == 0) {
      ++accepted;
    } else {
      ++refused;
      EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << name << ": one line";
      EXPECT_THAT(output, HasSubstr(name)) << name << ": the message names the file";
      std::string listing;
      EXPECT_TRUE(EmptyFolder(out, &listing)) << name << ": left " << listing;
    }
    std::filesystem::remove_all(out);
    std::filesystem::remove_all(path);
  }
  std::printf("%s: %zu variants, %d refused, %d accepted\n", fixture.name, variants.size(), refused, accepted);
  EXPECT_GT(refused, 0);
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, MalformedInputSweep, ::testing::ValuesIn(kFixtures),
                         [](const ::testing::TestParamInfo<Fixture>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace mocapsolve
