// Test support: real-data paths (MOCAPSOLVE_DATA), golden files, CLI runs.
#ifndef MOCAPSOLVE_TESTS_TEST_SUPPORT_H_
#define MOCAPSOLVE_TESTS_TEST_SUPPORT_H_

#include <string>
#include <vector>

#include <gtest/gtest.h>

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
std::string TempPath(const std::string& name);        // A fresh path in a per-test dir.

// Golden tables: tests/data/golden/<name>.csv, a header line then rows of numbers.
// Compare mode (default): every value must match within abs_tolerance. Update mode
// (the test binary run with --update_golden): the file is rewritten instead.
bool UpdateGoldenMode();
void ExpectMatchesGolden(const std::string& name, const std::vector<std::string>& columns,
                         const std::vector<std::vector<double>>& rows, double abs_tolerance);

// Runs the built CLI with arguments (shell-quoted by the caller); returns its exit code
// and fills *output with stdout+stderr.
int RunCli(const std::string& arguments, std::string* output);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_TEST_SUPPORT_H_
