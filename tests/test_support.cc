#include "tests/test_support.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mocapsolve::testing {
bool g_update_golden = false;  // Set by main from --update_golden.

bool FileExists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteTextFile(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    ADD_FAILURE() << path << ": cannot write";
    return;
  }
  if (std::fwrite(text.data(), 1, text.size(), file) != text.size()) ADD_FAILURE() << path << ": short write";
  std::fclose(file);
}

std::string DataRoot() {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  if (env != nullptr && *env != '\0') return env;
  return std::string(MOCAPSOLVE_SOURCE_DIR) + "/../shared/data";
}

std::string FindDataFile(const std::string& relative) {
  const std::string path = DataRoot() + "/" + relative;
  return FileExists(path) ? path : "";
}

bool DataRequired() {
  const char* env = std::getenv("MOCAPSOLVE_REQUIRE_DATA");
  return env != nullptr && std::string(env) == "1";
}

std::string SourcePath(const std::string& relative) {
  return std::string(MOCAPSOLVE_SOURCE_DIR) + "/" + relative;
}

std::string TempPath(const std::string& name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string dir = ::testing::TempDir() + "mocapsolve_" + std::to_string(::getpid());
  // pids are reused (pid_max is often 32768 and the suite starts thousands of processes):
  // a folder left by an earlier process with this pid goes, once per process.
  static const bool fresh = [&dir] {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
    return true;
  }();
  (void)fresh;
  ::mkdir(dir.c_str(), 0755);
  if (info != nullptr) {
    // Parameterized names hold '/': keep the test's folder one level deep.
    std::string test = std::string(info->test_suite_name()) + "." + info->name();
    for (char& c : test) {
      if (c == '\\' || c == '/') c = '_';
    }
    dir += "/" + test;
    ::mkdir(dir.c_str(), 0755);
  }
  return dir + "/" + name;
}

bool UpdateGoldenMode() { return g_update_golden; }

void ExpectMatchesGolden(const std::string& name, const std::vector<std::string>& columns,
                         const std::vector<std::vector<double>>& rows, double abs_tolerance) {
  const std::string path = SourcePath("tests/data/golden/" + name + ".csv");
  if (g_update_golden) {
    std::ofstream out(path);
    ASSERT_TRUE(out) << "cannot write " << path;
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
    out << "\n" << std::setprecision(10);
    for (const auto& row : rows) {
      for (size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
      out << "\n";
    }
    std::printf("updated golden file %s\n", path.c_str());
    return;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << "missing golden file " << path << " (run the test with --update_golden)";
  std::string line;
  std::getline(in, line);
  std::string expected_header;
  for (size_t c = 0; c < columns.size(); ++c) expected_header += (c ? "," : "") + columns[c];
  ASSERT_EQ(line, expected_header) << path << ": header";
  size_t r = 0;
  int reported = 0;
  for (; std::getline(in, line); ++r) {
    ASSERT_LT(r, rows.size()) << path << ": more rows than computed";
    std::stringstream ss(line);
    std::string cell;
    size_t c = 0;
    for (; std::getline(ss, cell, ','); ++c) {
      ASSERT_LT(c, rows[r].size()) << path << ":" << r + 2 << ": too many columns";
      const double golden = std::strtod(cell.c_str(), nullptr);
      if (!(std::abs(golden - rows[r][c]) <= abs_tolerance) && reported++ < 10) {
        ADD_FAILURE() << path << ":" << r + 2 << " column " << columns[c] << ": golden "
                      << golden << ", computed " << rows[r][c] << " (tolerance "
                      << abs_tolerance << ")";
      }
    }
    ASSERT_EQ(c, rows[r].size()) << path << ":" << r + 2 << ": column count";
  }
  EXPECT_EQ(r, rows.size()) << path << ": fewer rows than computed";
}

int CheckAnnotatedBadFiles(const std::string& extension,
                           const std::function<Status(const std::string& path)>& read) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("tests/data/bad"))) {
    if (entry.path().extension() != extension ||
        entry.path().filename().string().rfind("bad_", 0) != 0) {
      continue;
    }
    const std::string path = entry.path().string();
    SCOPED_TRACE(path);
    std::ifstream in(path);
    std::string header;
    std::getline(in, header);
    const std::string tag = "# expect-error: line ";
    EXPECT_EQ(header.rfind(tag, 0), 0u) << "first line must be '" << tag << "N: text'";
    const size_t colon = header.find(": ", tag.size());
    if (header.rfind(tag, 0) != 0 || colon == std::string::npos) continue;
    const std::string line = header.substr(tag.size(), colon - tag.size());
    const std::string expected = header.substr(colon + 2);
    const Status status = read(path);
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.message().rfind(path + ":" + line + ": ", 0), 0u) << status.message();
    EXPECT_NE(status.message().find(expected), std::string::npos) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    ++checked;
  }
  return checked;
}

std::string RandomlyDamaged(const std::string& base, const std::string& alphabet, std::mt19937* rng) {
  std::string text = base;
  const int edits = 1 + static_cast<int>((*rng)() % 4);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const size_t at = (*rng)() % text.size();
    switch ((*rng)() % 4) {
      case 0: text[at] = alphabet[(*rng)() % alphabet.size()]; break;
      case 1: text.erase(at, 1 + (*rng)() % 20); break;
      case 2: text.insert(at, 1, alphabet[(*rng)() % alphabet.size()]); break;
      case 3: text.resize(at); break;
    }
  }
  return text;
}

int RunProgram(const std::string& program, const std::string& arguments, std::string* output) {
  const std::string command = program + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  output->clear();
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output->append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string CliPath() { return MOCAPSOLVE_CLI; }

int RunCli(const std::string& arguments, std::string* output) {
  return RunProgram(CliPath(), arguments, output);
}

std::string BuiltProgramPath(const std::string& name) {
  const std::string cli = CliPath();
  const size_t slash = cli.rfind('/');
  return (slash == std::string::npos ? std::string(".") : cli.substr(0, slash)) + "/" + name;
}

}  // namespace mocapsolve::testing

// The test main: gtest flags, plus --update_golden to rewrite golden files.
int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--update_golden") == 0) mocapsolve::testing::g_update_golden = true;
  }
  return RUN_ALL_TESTS();
}
