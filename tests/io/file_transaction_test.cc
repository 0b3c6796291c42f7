// FileTransaction and StagedFile (io/file_transaction.h, io/atomic_file.h): inputs are
// never overwritten, outputs appear together or not at all, nothing partial is left
// behind, streams are written into rather than replaced.
#include "io/file_transaction.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/content_hash.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

void WriteNow(const std::string& path, const std::string& text) {
  ASSERT_TRUE(WriteFileAtomically(path, text).ok()) << path;
}

std::string Folder(const std::string& path) { return path.substr(0, path.find_last_of('/')); }

// The names in a folder (without . and ..).
std::set<std::string> Listing(const std::string& folder) {
  std::set<std::string> names;
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return names;
  while (dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.insert(name);
  }
  ::closedir(dir);
  return names;
}

TEST(FileTransaction, OutputsAppearOnlyAtCommit) {
  const std::string a = testing::TempPath("a.txt"), b = testing::TempPath("b.txt");
  FileTransaction files;
  ASSERT_TRUE(WriteFileAtomically(a, "alpha").ok());
  ASSERT_TRUE(WriteFileAtomically(b, "beta").ok());
  EXPECT_FALSE(testing::FileExists(a));
  EXPECT_FALSE(testing::FileExists(b));
  EXPECT_EQ(files.num_staged(), 2);
  ASSERT_TRUE(files.Commit().ok());
  EXPECT_EQ(testing::ReadTextFile(a), "alpha");
  EXPECT_EQ(testing::ReadTextFile(b), "beta");
  EXPECT_EQ(Listing(Folder(a)), (std::set<std::string>{"a.txt", "b.txt"}));  // No temporaries.
}

// A file written in pieces (AtomicFileWriter: a long take's outputs) is staged like the
// others: nothing under its name until Commit, then the pieces in order; an input as its
// path is refused at Close; dropped unclosed, nothing is left.
TEST(FileTransaction, FileWrittenInPiecesAppearsAtCommit) {
  const std::string a = testing::TempPath("pieces.txt"), input = testing::TempPath("input.txt");
  WriteNow(input, "in");
  {
    FileTransaction files;
    AtomicFileWriter writer;
    ASSERT_TRUE(writer.Open(a).ok());
    ASSERT_TRUE(writer.Append("alpha ").ok());
    ASSERT_TRUE(writer.Append("beta", 4).ok());
    ASSERT_TRUE(writer.Close().ok());
    EXPECT_FALSE(testing::FileExists(a));
    EXPECT_EQ(files.num_staged(), 1);
    std::string text;
    ASSERT_TRUE(ReadFileToString(input, &text).ok());
    AtomicFileWriter over_input;
    ASSERT_TRUE(over_input.Open(input).ok());
    EXPECT_THAT(over_input.Close().message(), HasSubstr("would overwrite the input"));
    AtomicFileWriter dropped;
    ASSERT_TRUE(dropped.Open(testing::TempPath("dropped.txt")).ok());
    ASSERT_TRUE(dropped.Append("never").ok());
    ASSERT_TRUE(files.Commit().ok());
  }
  EXPECT_EQ(testing::ReadTextFile(a), "alpha beta");
  EXPECT_EQ(testing::ReadTextFile(input), "in");
  EXPECT_EQ(Listing(Folder(a)), (std::set<std::string>{"pieces.txt", "input.txt"}));
}

TEST(FileTransaction, FailedCommandPublishesNothingAndLeavesNothing) {
  const std::string a = testing::TempPath("a.txt");
  WriteNow(a, "old");
  {
    FileTransaction files;
    ASSERT_TRUE(WriteFileAtomically(a, "new").ok());
    // No Commit: the command failed.
  }
  EXPECT_EQ(testing::ReadTextFile(a), "old");
  EXPECT_EQ(Listing(Folder(a)), (std::set<std::string>{"a.txt"}));
}

// The folders a failed command made for its outputs go with them (a long take that fails
// in its third window left an empty take folder); a folder that was there before, one
// that holds a file, and those of a committed command stay.
TEST(FileTransaction, FailedCommandLeavesNoFolderItMade) {
  const std::string root = Folder(testing::TempPath("x")) + "/made_folders";
  ASSERT_TRUE(MakeFolders(root).ok());  // There before: stays.
  {
    FileTransaction files;
    ASSERT_TRUE(MakeFolders(root + "/take/deep").ok());
    ASSERT_TRUE(MakeFolders(root + "/kept").ok());
    ASSERT_TRUE(WriteFileAtomically(root + "/take/deep/out.txt", "never").ok());
    std::FILE* other = std::fopen((root + "/kept/someone_elses.txt").c_str(), "w");  // Not staged.
    ASSERT_NE(other, nullptr);
    std::fclose(other);
  }
  EXPECT_EQ(Listing(root), (std::set<std::string>{"kept"}));
  EXPECT_EQ(Listing(root + "/kept"), (std::set<std::string>{"someone_elses.txt"}));
  {
    FileTransaction files;
    ASSERT_TRUE(MakeFolders(root + "/done/empty").ok());
    ASSERT_TRUE(files.Commit().ok());
  }
  EXPECT_EQ(Listing(root), (std::set<std::string>{"done", "kept"}));
  EXPECT_EQ(Listing(root + "/done"), (std::set<std::string>{"empty"}));
}

TEST(FileTransaction, RefusesToOverwriteAnInput) {
  const std::string input = testing::TempPath("set.json");
  WriteNow(input, "{\"markers\": []}");
  FileTransaction files;
  std::string text;
  ASSERT_TRUE(ReadFileToString(input, &text).ok());
  const Status status = WriteFileAtomically(input, "report");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("would overwrite the input"));
  EXPECT_EQ(status.message().find('\n'), std::string::npos);
  EXPECT_TRUE(files.Commit().ok());
  EXPECT_EQ(testing::ReadTextFile(input), "{\"markers\": []}");
}

TEST(FileTransaction, UntrackedReadsAreNotInputs) {
  // The batch reads back its takes' reports and records: neither inputs nor outputs.
  const std::string read_back = testing::TempPath("record.json");
  const std::string input = testing::TempPath("input.json");
  WriteNow(read_back, "{}");
  WriteNow(input, "{}");
  FileTransaction files;
  std::string text;
  {
    FileTransaction::UntrackedReads untracked;
    ASSERT_TRUE(ReadFileToString(read_back, &text).ok());
  }
  ASSERT_TRUE(ReadFileToString(input, &text).ok());
  EXPECT_FALSE(files.NamesAnInput(read_back));
  EXPECT_TRUE(files.NamesAnInput(input));
}

TEST(FileTransaction, RefusesInputsUnderOtherNames) {
  const std::string input = testing::TempPath("take.c3d");
  WriteNow(input, "bytes");
  const std::string folder = Folder(input);
  const std::string link = folder + "/link.c3d", hard = folder + "/hard.c3d";
  ASSERT_EQ(::symlink(input.c_str(), link.c_str()), 0);
  ASSERT_EQ(::link(input.c_str(), hard.c_str()), 0);
  FileTransaction files;
  std::string text;
  ASSERT_TRUE(ReadFileToString(input, &text).ok());
  for (const std::string& output : {link, hard, folder + "/./take.c3d", folder + "/../" +
                                    folder.substr(folder.find_last_of('/') + 1) + "/take.c3d"}) {
    EXPECT_FALSE(WriteFileAtomically(output, "x").ok()) << output;
  }
  EXPECT_EQ(testing::ReadTextFile(input), "bytes");
}

TEST(FileTransaction, InputReadAfterStagingIsCheckedAtCommit) {
  const std::string path = testing::TempPath("late.txt");
  WriteNow(path, "input");
  FileTransaction files;
  ASSERT_TRUE(WriteFileAtomically(path, "output").ok());
  std::string text;
  ASSERT_TRUE(ReadFileToString(path, &text).ok());
  EXPECT_EQ(text, "input");
  const Status status = files.Commit();
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("would overwrite the input"));
  EXPECT_EQ(testing::ReadTextFile(path), "input");
}

TEST(FileTransaction, TwoOutputsOnOnePathAreAnError) {
  const std::string out = testing::TempPath("x.bvh");
  FileTransaction files;
  ASSERT_TRUE(WriteFileAtomically(out, "HIERARCHY").ok());
  const Status status = WriteFileAtomically(Folder(out) + "/./x.bvh", "{}");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("named twice as an output"));
}

TEST(FileTransaction, StreamsAreWrittenIntoNotReplaced) {
  {
    FileTransaction files;
    ASSERT_TRUE(WriteFileAtomically("/dev/null", "nothing").ok());
    ASSERT_TRUE(files.Commit().ok());
  }
  struct stat st;
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // A full disk: the error names the file, and the regular outputs are not published.
  const std::string other = testing::TempPath("other.txt");
  FileTransaction files;
  ASSERT_TRUE(WriteFileAtomically(other, "x").ok());
  ASSERT_TRUE(WriteFileAtomically("/dev/full", "x").ok());
  const Status status = files.Commit();
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("/dev/full"));
  EXPECT_FALSE(testing::FileExists(other));
}

TEST(FileTransaction, UnwritableTargetsFailAtOnce) {
  FileTransaction files;
  EXPECT_FALSE(WriteFileAtomically(testing::TempPath("no/such/folder/x.json"), "x").ok());
  EXPECT_FALSE(WriteFileAtomically(Folder(testing::TempPath("d.json")), "x").ok());  // A directory.
  // A read-only file system (root may write anywhere else).
  const Status status = WriteFileAtomically("/proc/mocapsolve_test.json", "x");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("/proc/mocapsolve_test.json: cannot write"));
}

TEST(FileTransaction, WithoutATransactionWritesAtOnce) {
  const std::string path = testing::TempPath("now.txt");
  WriteNow(path, "now");
  EXPECT_EQ(testing::ReadTextFile(path), "now");
  EXPECT_EQ(Listing(Folder(path)), (std::set<std::string>{"now.txt"}));
}

// A process killed at any moment while writing a large output: the old output stays
// whole or the new one is whole, and no other file appears.
TEST(FileTransaction, KilledWhileWritingLeavesOldOrNewWhole) {
  const std::string path = testing::TempPath("big.bin");
  const std::string old_text = "old output";
  WriteNow(path, old_text);
  const std::string new_text(48 << 20, 'n');
  for (int delay_us : {0, 2000, 20000, 200000}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      FileTransaction files;
      if (!WriteFileAtomically(path, new_text).ok()) ::_exit(2);
      if (!files.Commit().ok()) ::_exit(3);
      ::_exit(0);
    }
    ::usleep(delay_us);
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    const std::string now = testing::ReadTextFile(path);
    EXPECT_TRUE(now == old_text || now == new_text) << "delay " << delay_us << " us: " << now.size() << " bytes";
    EXPECT_EQ(Listing(Folder(path)), (std::set<std::string>{"big.bin"})) << "delay " << delay_us << " us";
    WriteNow(path, old_text);
  }
}

// Two processes writing the same output at once: one wins, whole.
TEST(FileTransaction, ConcurrentWritersOneWinsWhole) {
  const std::string path = testing::TempPath("shared.bin");
  const std::string a(8 << 20, 'a'), b(8 << 20, 'b');
  pid_t children[2];
  for (int i = 0; i < 2; ++i) {
    children[i] = ::fork();
    ASSERT_GE(children[i], 0);
    if (children[i] == 0) {
      FileTransaction files;
      const bool ok = WriteFileAtomically(path, i == 0 ? a : b).ok() && files.Commit().ok();
      ::_exit(ok ? 0 : 1);
    }
  }
  for (pid_t child : children) {
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  const std::string now = testing::ReadTextFile(path);
  EXPECT_TRUE(now == a || now == b);
  EXPECT_EQ(Listing(Folder(path)), (std::set<std::string>{"shared.bin"}));
}

}  // namespace
}  // namespace mocapsolve

namespace mocapsolve {
namespace {

// An input that another program truncates or rewrites while we read it: an error naming
// the file, not a shorter file parsed as if whole (a truncated BVH can parse as a shorter
// motion). The seam truncates the file after the first 64 KiB chunk.
void TruncateAfterFirstChunk(const std::string& path, size_t bytes_so_far) {
  if (bytes_so_far <= 65536) {
    ASSERT_EQ(::truncate(path.c_str(), 1000), 0);
  }
}
void AppendAfterFirstChunk(const std::string& path, size_t bytes_so_far) {
  if (bytes_so_far > 65536) return;
  FILE* file = std::fopen(path.c_str(), "a");
  ASSERT_NE(file, nullptr);
  std::fputs("more\n", file);
  std::fclose(file);
}

TEST(ReadFileToString, AnInputChangedDuringTheReadIsAnError) {
  const std::string path = testing::TempPath("growing.bvh");
  const std::string text(300000, 'x');
  std::string read;
  for (auto observer : {TruncateAfterFirstChunk, AppendAfterFirstChunk}) {
    WriteNow(path, text);
    SetReadChunkObserverForTesting(observer);
    const Status status = ReadFileToString(path, &read);
    SetReadChunkObserverForTesting(nullptr);
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.message(), HasSubstr(path + ": the file changed while it was read"));
    EXPECT_EQ(status.message().find('\n'), std::string::npos);
  }
  WriteNow(path, text);  // Unchanged: read whole.
  ASSERT_TRUE(ReadFileToString(path, &read).ok());
  EXPECT_EQ(read, text);
}

// Every reader goes through OpenRegularFile: a FIFO (no writer: opening it for reading
// would block for ever), a folder or a device is refused at once, naming the path and what
// it is, and the content hash (a batch's keys) refuses the same.
TEST(OpenRegularFile, RefusesFifosFoldersAndDevicesWithoutBlocking) {
  const std::string fifo = testing::TempPath("pipe.c3d");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string text;
  Status status = ReadFileToString(fifo, &text);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), fifo + ": is not a regular file (a FIFO)");
  uint64_t hash = 0;
  status = HashFile(fifo, &hash);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), fifo + ": is not a regular file (a FIFO)");
  status = ReadFileToString(Folder(fifo), &text);
  EXPECT_THAT(status.message(), HasSubstr("is not a regular file (a folder)"));
  status = ReadFileToString("/dev/zero", &text);  // Would never end.
  EXPECT_EQ(status.message(), "/dev/zero: is not a regular file (a character device)");
  status = ReadFileToString(testing::TempPath("missing.json"), &text);
  EXPECT_THAT(status.message(), HasSubstr("missing.json: cannot open (No such file or directory)"));
  const std::string regular = testing::TempPath("ok.json");
  testing::WriteTextFile(regular, "{}");
  ASSERT_TRUE(ReadFileToString(regular, &text).ok());
  EXPECT_EQ(text, "{}");
}

}  // namespace
}  // namespace mocapsolve
