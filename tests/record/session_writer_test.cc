// The session file: readable as a log after every Flush, after the process
// is interrupted (SIGINT: the loop leaves, the destructor finishes) or
// killed (SIGKILL: what was flushed is there), and never a device, a link
// or the input.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/live_source.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::ScratchDir;

std::string AccelLines(int rows, int first = 0) {
  std::string text;
  for (int i = first; i < first + rows; ++i) {
    text += fmt::format("{:.2f},0.01,-0.02,{:.4f}\n", 0.01 * i, 9.81 + 0.001 * (i % 7));
  }
  return text;
}

TEST(SessionWriter, TheFileIsAReadableLogAfterEveryFlush) {
  ScratchDir dir;
  const std::string path = dir.Path("session.csv");
  SessionWriter writer(path, "-");
  EXPECT_FALSE(std::filesystem::exists(path));  // created at the first text
  LiveLogParser parser({}, "live");
  Recording rows;
  std::size_t total = 0;
  for (int block = 0; block < 4; ++block) {
    parser.Feed(AccelLines(60, 60 * block), &rows);
    writer.Write(parser.TakeSessionText());
    writer.Flush();
    total = rows.size();
    const Recording back = ReadLog(path, {});
    EXPECT_EQ(back.size(), total) << "after block " << block;
    EXPECT_EQ(back.time_s.back(), rows.time_s.back());
  }
  EXPECT_EQ(total, 240u);
  EXPECT_TRUE(writer.Close());
  EXPECT_EQ(ReadFile(path), "t,ax,ay,az\n" + AccelLines(240));
}

TEST(SessionWriter, NoTextNoFile) {
  ScratchDir dir;
  const std::string path = dir.Write("old.csv", "t,ax,ay,az\n0,0,0,9.8\n");
  {
    SessionWriter writer(path, "-");
    EXPECT_FALSE(writer.Close());
  }
  EXPECT_EQ(ReadFile(path), "t,ax,ay,az\n0,0,0,9.8\n");  // nothing came: not replaced
}

TEST(SessionWriter, NeverADeviceALinkADirectoryOrTheInput) {
  ScratchDir dir;
  const std::string target = dir.Write("target.csv", "keep\n");
  const std::string link = dir.Path("link.csv");
  std::filesystem::create_symlink(target, link);
  EXPECT_THAT([&] { SessionWriter(link, "-"); },
              ::testing::ThrowsMessage<Error>(HasSubstr("is a symbolic link")));
  EXPECT_THAT(
      [] { SessionWriter("/dev/null", "-"); },
      ::testing::ThrowsMessage<Error>(HasSubstr("is a device, a FIFO or a socket")));
  const std::string fifo = dir.Path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(
      [&] { SessionWriter(fifo, "-"); },
      ::testing::ThrowsMessage<Error>(HasSubstr("is a device, a FIFO or a socket")));
  EXPECT_THAT([&] { SessionWriter(dir.path().string(), "-"); },
              ::testing::ThrowsMessage<Error>(HasSubstr("is a directory")));
  EXPECT_THAT([&] { SessionWriter(dir.Path("no/such/dir/s.csv"), "-"); },
              ::testing::ThrowsMessage<Error>(HasSubstr("does not exist")));
  EXPECT_THAT([&] { SessionWriter(target, target); },
              ::testing::ThrowsMessage<Error>(HasSubstr("does not overwrite its input")));
  EXPECT_THAT([] { SessionWriter("-", "-"); },
              ::testing::ThrowsMessage<Error>(HasSubstr("written to a file")));
  EXPECT_EQ(ReadFile(target), "keep\n");
}

// A child writes a session as a recording loop does (its SIGINT handler
// sets a flag; the loop leaves; the writer's destructor finishes) until the
// parent interrupts or kills it; the parent reads the file with ReadLog.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void OnInterrupt(int) { g_interrupted = 1; }

[[noreturn]] void RecordUntilStopped(const std::string& path, int ready_fd) {
  struct sigaction sa {};
  sa.sa_handler = OnInterrupt;
  ::sigaction(SIGINT, &sa, nullptr);
  int code = 0;
  {
    SessionWriter writer(path, "-");
    LiveLogParser parser({}, "live");
    Recording rows;
    for (int block = 0; !g_interrupted && block < 100000; ++block) {
      parser.Feed(AccelLines(50, 50 * block), &rows);
      rows.time_s.clear();
      rows.accel.clear();
      writer.Write(parser.TakeSessionText());
      if (block % 4 == 3) writer.Flush();  // a captured position
      if (block == 8) {
        const char c = 'r';
        if (::write(ready_fd, &c, 1) != 1) code = 3;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (!g_interrupted) code = 4;
  }
  ::_exit(code);
}

pid_t StartRecording(const std::string& path) {
  int fds[2];
  EXPECT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(fds[0]);
    RecordUntilStopped(path, fds[1]);
  }
  ::close(fds[1]);
  char c = 0;
  EXPECT_EQ(::read(fds[0], &c, 1), 1);  // it has written a few positions
  ::close(fds[0]);
  return child;
}

TEST(SessionWriter, CtrlCLeavesACompleteReadableLog) {
  ScratchDir dir;
  const std::string path = dir.Path("session.csv");
  const pid_t child = StartRecording(path);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ASSERT_EQ(::kill(child, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const Recording back = ReadLog(path, {});
  EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();  // no cut line: complete
  ASSERT_GE(back.size(), 450u);
  EXPECT_EQ(back.size() % 50, 0u);  // whole blocks, as fed
  EXPECT_EQ(ReadFile(path), "t,ax,ay,az\n" + AccelLines(static_cast<int>(back.size())));
}

TEST(SessionWriter, AKilledProcessLeavesWhatWasFlushed) {
  ScratchDir dir;
  const std::string path = dir.Path("session.csv");
  const pid_t child = StartRecording(path);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const Recording back = ReadLog(path, {});
  EXPECT_GE(back.size(), 400u);  // at least the 8 blocks flushed before "ready"
  // A prefix of the stream, whole rows in time order.
  for (std::size_t i = 0; i < back.size(); ++i) {
    ASSERT_NEAR(back.time_s[i], 0.01 * static_cast<double>(i), 1e-9);
  }
}

}  // namespace
}  // namespace mpcal
