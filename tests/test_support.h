// Test support: real-data paths (MOCAPSOLVE_DATA), golden files, CLI runs.
#ifndef MOCAPSOLVE_TESTS_TEST_SUPPORT_H_
#define MOCAPSOLVE_TESTS_TEST_SUPPORT_H_

#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/status.h"

namespace mocapsolve::testing {

// MOCAPSOLVE_DATA or, unset, ../shared/data beside the source tree.
std::string DataRoot();
// Path of a file under the data root ("bvh/01_01.bvh"); "" if it is not there.
std::string FindDataFile(const std::string& relative);
bool DataRequired();  // MOCAPSOLVE_REQUIRE_DATA=1

// Sets *path to the data file or skips the test with a message (fails instead when
// MOCAPSOLVE_REQUIRE_DATA=1). Use as: MOCAPSOLVE_DATA_FILE(path, "bvh/01_01.bvh");
#define MOCAPSOLVE_DATA_FILE(path, relative)                                                 \
  std::string path = ::mocapsolve::testing::FindDataFile(relative);                          \
  if (path.empty()) {                                                                        \
    if (::mocapsolve::testing::DataRequired()) {                                             \
      FAIL() << "missing data file " << ::mocapsolve::testing::DataRoot() << "/" << relative \
             << " (MOCAPSOLVE_REQUIRE_DATA=1)";                                              \
    }                                                                                        \
    GTEST_SKIP() << "data file " << relative << " not found under "                          \
                 << ::mocapsolve::testing::DataRoot() << " (set MOCAPSOLVE_DATA)";           \
  }

std::string SourcePath(const std::string& relative);  // Under the repository root.
bool FileExists(const std::string& path);
std::string ReadTextFile(const std::string& path);     // "" if it cannot be read.
void WriteTextFile(const std::string& path, const std::string& text);  // Every byte; a failure fails the test.
std::string TempPath(const std::string& name);        // A fresh path in a per-test dir.

// Golden tables: tests/data/golden/<name>.csv, a header line then rows of numbers.
// Compare mode (default): every value must match within abs_tolerance. Update mode
// (the test binary run with --update_golden): the file is rewritten instead.
bool UpdateGoldenMode();
void ExpectMatchesGolden(const std::string& name, const std::vector<std::string>& columns,
                         const std::vector<std::vector<double>>& rows, double abs_tolerance);

// For each tests/data/bad/bad_*<extension> (e.g. ".asf"), whose first line must read
// "# expect-error: line N: <part of the message>": `read` must fail with one line that
// starts "<path>:N: " and contains that part. Returns how many files were checked.
int CheckAnnotatedBadFiles(const std::string& extension,
                           const std::function<Status(const std::string& path)>& read);

// `text` with 1-4 random edits (a byte replaced from `alphabet`, up to 20 bytes erased, a
// byte inserted, or the rest cut), for robustness tests of parsers.
std::string RandomlyDamaged(const std::string& text, const std::string& alphabet, std::mt19937* rng);

// Path of the built CLI (build/bin/mocapsolve). The paths are compiled into
// test_support.cc alone, so that every test file compiles the same in every build folder
// (ccache serves the sanitized build's tests from the Release build's).
std::string CliPath();
// Runs the built CLI with arguments (shell-quoted by the caller); returns its exit code
// and fills *output with stdout+stderr.
int RunCli(const std::string& arguments, std::string* output);
// The same for another program (a path); stdout+stderr into *output.
int RunProgram(const std::string& program, const std::string& arguments, std::string* output);
// Path of another executable built beside the CLI (build/bin/<name>); it may not exist.
std::string BuiltProgramPath(const std::string& name);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_TEST_SUPPORT_H_
