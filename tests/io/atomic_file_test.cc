#include "mpcal/atomic_file.h"

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ReadFile;
using mpcal::testing::ScratchDir;
using ::testing::HasSubstr;

std::size_t FilesIn(const ScratchDir& dir) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    (void)entry;
    ++n;
  }
  return n;
}

TEST(AtomicFile, WritesAndReplacesWholeFiles) {
  ScratchDir dir;
  const std::string path = dir.Path("out.txt");
  WriteFileAtomically(path, "first\n");
  EXPECT_EQ(ReadFile(path), "first\n");
  WriteFileAtomically(path, "second\n");
  EXPECT_EQ(ReadFile(path), "second\n");
  EXPECT_EQ(FilesIn(dir), 1u);  // no temporary file left beside it
}

TEST(AtomicFile, StreamsLargeContent) {
  ScratchDir dir;
  const std::string path = dir.Path("big.txt");
  std::string expected;
  for (int i = 0; i < 300000; ++i) expected += std::to_string(i) + "\n";
  WriteStreamAtomically(path, [&](std::ostream& out) {
    for (int i = 0; i < 300000; ++i) out << i << '\n';
  });
  EXPECT_EQ(ReadFile(path), expected);
}

TEST(AtomicFile, GetsOrdinaryPermissions) {
  ScratchDir dir;
  const std::string path = dir.Path("perm.txt");
  WriteFileAtomically(path, "x");
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  const mode_t mask = umask(0);
  umask(mask);
  EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask);
}

TEST(AtomicFile, FailureInTheMiddleLeavesNothingAndKeepsTheOldFile) {
  ScratchDir dir;
  const std::string path = dir.Path("out.txt");
  EXPECT_THROW(WriteStreamAtomically(path,
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw Error("input broke");
                                     }),
               Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(FilesIn(dir), 0u);

  WriteFileAtomically(path, "old\n");
  EXPECT_THROW(WriteStreamAtomically(path,
                                     [](std::ostream& out) {
                                       out << "new";
                                       throw std::runtime_error("bug");
                                     }),
               std::runtime_error);
  EXPECT_EQ(ReadFile(path), "old\n");
  EXPECT_EQ(FilesIn(dir), 1u);
}

TEST(AtomicFile, CheckWritableBeforeAnyWork) {
  ScratchDir dir;
  EXPECT_NO_THROW(CheckWritable(dir.Path("out.txt")));
  EXPECT_NO_THROW(CheckWritable("-"));
  EXPECT_EQ(FilesIn(dir), 0u);  // checking writes nothing
  try {
    CheckWritable(dir.Path("no/such/dir/out.txt"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("does not exist; create it, or give another path"));
  }
  EXPECT_THROW(CheckWritable(dir.path().string()), Error);
  EXPECT_THROW(CheckWritable(""), Error);
}

TEST(AtomicFile, CheckOutputRefusesEveryInputGivenAndSkipsTheEmptyOnes) {
  ScratchDir dir;
  const std::string log = dir.Write("log.csv", "t,ax,ay,az\n");
  EXPECT_NO_THROW(CheckOutput(dir.Path("out.json"), {log, ""}));
  EXPECT_THROW(CheckOutput(log, {"", log}), Error);
  EXPECT_THROW(CheckOutput(dir.Path("no/such/out.json"), {log}), Error);
}

TEST(AtomicFile, MissingDirectoryOrDirectoryTarget) {
  ScratchDir dir;
  try {
    WriteFileAtomically(dir.Path("no/such/dir/out.txt"), "x");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("does not exist"));
  }
  try {
    WriteFileAtomically(dir.path().string(), "x");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a directory"));
  }
}

TEST(AtomicFile, UnwritableDirectory) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes anywhere";
  ScratchDir dir;
  std::filesystem::create_directory(dir.path() / "ro");
  std::filesystem::permissions(
      dir.path() / "ro",
      std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  EXPECT_THROW(WriteFileAtomically((dir.path() / "ro" / "out.txt").string(), "x"), Error);
  std::filesystem::permissions(dir.path() / "ro", std::filesystem::perms::owner_all);
}

// A rename over a device node or a link would replace it with a regular
// file (as root, `-o /dev/null` would replace the system's): the link is
// followed and its target replaced instead.
TEST(AtomicFile, SymlinkIsFollowedAndItsTargetReplaced) {
  ScratchDir dir;
  const std::string target = dir.Write("target.json", "old");
  const std::string link = dir.Path("link.json");
  std::filesystem::create_symlink("target.json", link);
  WriteFileAtomically(link, "new");
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(ReadFile(target), "new");
  // A dangling link: the file it names is created.
  const std::string dangling = dir.Path("dangling.json");
  std::filesystem::create_symlink("created.json", dangling);
  WriteFileAtomically(dangling, "made");
  EXPECT_TRUE(std::filesystem::is_symlink(dangling));
  EXPECT_EQ(ReadFile(dir.Path("created.json")), "made");
}

TEST(AtomicFile, FifoIsWrittenInPlace) {
  ScratchDir dir;
  const std::string fifo = dir.Path("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = ReadFile(fifo); });
  WriteFileAtomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(AtomicFile, DeviceNodesAreWrittenInPlaceNeverReplaced) {
  if (geteuid() != 0) GTEST_SKIP() << "mknod needs root";
  ScratchDir dir;
  const std::string null = dir.Path("null");
  const std::string full = dir.Path("full");
  ASSERT_EQ(::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  ASSERT_EQ(::mknod(full.c_str(), S_IFCHR | 0666, makedev(1, 7)), 0);
  EXPECT_NO_THROW(CheckOutput(null, {null}));  // a device named twice overwrites nothing
  WriteFileAtomically(null, "discarded");
  try {
    WriteFileAtomically(full, "no room");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("No space left on device"));
  }
  for (const std::string& node : {null, full}) {
    struct stat st {};
    ASSERT_EQ(::lstat(node.c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << node << " was replaced";
  }
  EXPECT_EQ(FilesIn(dir), 2u);
}

TEST(AtomicFile, EmptyNameAndClosedDescriptorAreRefused) {
  EXPECT_THROW(WriteFileAtomically("", "x"), Error);
  try {
    CheckWritable("/dev/fd/987");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("file descriptor 987 is closed"));
  }
}

TEST(RefuseOverwritingInput, SamePathLinkAndDifferentFiles) {
  ScratchDir dir;
  const std::string input = dir.Write("in.csv", "t,ax,ay,az\n");
  EXPECT_THROW(RefuseOverwritingInput(input, input), Error);
  EXPECT_THROW(RefuseOverwritingInput(input, (dir.path() / "." / "in.csv").string()),
               Error);
  std::filesystem::create_hard_link(input, dir.Path("hard.csv"));
  EXPECT_THROW(RefuseOverwritingInput(input, dir.Path("hard.csv")), Error);
  std::filesystem::create_symlink(input, dir.Path("soft.csv"));
  EXPECT_THROW(RefuseOverwritingInput(dir.Path("soft.csv"), input), Error);
  EXPECT_NO_THROW(RefuseOverwritingInput(input, dir.Path("out.csv")));
  EXPECT_NO_THROW(RefuseOverwritingInput("-", "-"));
  EXPECT_NO_THROW(RefuseOverwritingInput(input, "-"));
}

}  // namespace
}  // namespace mpcal
