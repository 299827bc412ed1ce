#include "mpcal/text_input.h"

#include <unistd.h>

#include <csignal>

#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ScratchDir;
using ::testing::HasSubstr;

std::string ErrorOf(const std::string& path, std::size_t max_bytes) {
  try {
    ReadTextInput(path, max_bytes, "calibration file");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TextInput, ReadsARegularFileWhole) {
  ScratchDir dir;
  const std::string path = dir.Write("c.json", "{\"format\": 1}\n");
  EXPECT_EQ(ReadTextInput(path, 100, "calibration file"), "{\"format\": 1}\n");
}

// A device is refused before any byte is read (/dev/zero would give 0.9 GB in 20 s).
TEST(TextInput, RefusesDevicesBeforeReading) {
  EXPECT_THAT(ErrorOf("/dev/zero", 1 << 20),
              HasSubstr("'/dev/zero' is a character device, not a calibration file"));
  EXPECT_THAT(ErrorOf("/dev/urandom", 1 << 20), HasSubstr("is a character device"));
}

TEST(TextInput, RefusesLargeFilesBeforeReadingThem) {
  ScratchDir dir;
  const std::string path = dir.Write("big.json", std::string(5000, ' '));
  EXPECT_THAT(ErrorOf(path, 4096), HasSubstr("is larger than 0 MiB"));
}

TEST(TextInput, RefusesBinaryFromItsFirstBytes) {
  ScratchDir dir;
  const std::string path =
      dir.Write("png.json", std::string("\x89PNG\r\n\x1a\n\0\0", 10));
  EXPECT_THAT(ErrorOf(path, 1 << 20),
              HasSubstr("is not a text file (binary data at byte 8)"));
}

TEST(TextInput, ReadsAPipeAndStopsAtTheCap) {
  std::signal(SIGPIPE, SIG_IGN);  // the writer outlives the reader
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::thread writer([&] {
    const std::string chunk(1 << 16, 'x');
    for (int i = 0; i < 64; ++i) {
      if (::write(fds[1], chunk.data(), chunk.size()) < 0) break;  // reader gave up
    }
    ::close(fds[1]);
  });
  const std::string path = "/dev/fd/" + std::to_string(fds[0]);
  EXPECT_THAT(ErrorOf(path, 1 << 20), HasSubstr("is larger than 1 MiB"));
  ::close(fds[0]);
  writer.join();
}

}  // namespace
}  // namespace mpcal
