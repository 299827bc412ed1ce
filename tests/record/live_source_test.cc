// The live sources on this machine's own loopback: standard input through a
// pipe, a TCP server and a UDP sender in a thread, a pseudo-terminal pair
// standing in for a serial port; and what each does when the stream stops,
// ends, or cannot be opened.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
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
using Clock = std::chrono::steady_clock;

std::string ImuLines(int rows, int first = 0) {
  std::string text;
  for (int i = first; i < first + rows; ++i) {
    text += fmt::format(
        "{:.2f},0.01,-0.02,{:.4f},0.001,0.002,0.003\n", 0.01 * i, 9.81 + 0.001 * (i % 7));
  }
  return text;
}

void WriteAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    ASSERT_GT(n, 0);
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

// Everything a source gives until its end (or `want` bytes).
std::string Drain(LiveSource* source, std::size_t want = std::string::npos) {
  std::string got;
  while (got.size() < want && source->Read(&got, 0.05)) {
  }
  return got;
}

// The text sent in pieces with pauses, as a logger sends it.
void SendPaced(int fd, const std::string& text) {
  for (std::size_t at = 0; at < text.size(); at += 700) {
    WriteAll(fd, std::string_view(text).substr(at, 700));
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
}

// Standard input replaced by a pipe's read end for one test.
class StdinPipe {
 public:
  StdinPipe() {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    saved_ = ::dup(STDIN_FILENO);
    ::dup2(fds[0], STDIN_FILENO);
    ::close(fds[0]);
    write_fd_ = fds[1];
  }
  ~StdinPipe() {
    CloseWriter();
    ::dup2(saved_, STDIN_FILENO);
    ::close(saved_);
  }
  int write_fd() const { return write_fd_; }
  void CloseWriter() {
    if (write_fd_ >= 0) ::close(write_fd_);
    write_fd_ = -1;
  }

 private:
  int saved_ = -1;
  int write_fd_ = -1;
};

TEST(LiveSource, StandardInputThroughAPipeToItsEnd) {
  StdinPipe pipe;
  const std::string text = ImuLines(300);
  auto source = OpenLiveSource({"-"});
  EXPECT_EQ(source->source(), "<stdin>");
  std::thread writer([&] {
    SendPaced(pipe.write_fd(), text);
    pipe.CloseWriter();
  });
  const std::string got = Drain(source.get());
  writer.join();
  EXPECT_EQ(got, text);
  EXPECT_EQ(source->bytes_received(), text.size());
  // At the end, it stays at the end.
  std::string more;
  EXPECT_FALSE(source->Read(&more, 0.01));
  EXPECT_TRUE(more.empty());
}

// The whole chain a user tries first: `mpcal simulate static --realtime`
// into standard input, parsed as it arrives, written as the session file:
// the rows are those ReadLog reads from the file simulate writes at once,
// and from the session file.
TEST(LiveSource, ASimulatedSessionAtItsPaceThroughStandardInput) {
  testing::ScratchDir dir;
  const std::string session =
      "simulate static --preset mti-g --seed 5 --positions 6 --dwell 2 --turn 1 --rest 1 "
      "--gyro";
  ASSERT_EQ(
      std::system(
          fmt::format(
              "'{}' {} -o '{}' >/dev/null", MPCAL_BINARY, session, dir.Path("whole.csv"))
              .c_str()),
      0);
  const Recording whole = ReadLog(dir.Path("whole.csv"), {});
  std::FILE* pipe = ::popen(
      fmt::format("'{}' {} --speed 20 -o - 2>/dev/null", MPCAL_BINARY, session).c_str(),
      "r");
  ASSERT_NE(pipe, nullptr);
  const int saved = ::dup(STDIN_FILENO);
  ::dup2(::fileno(pipe), STDIN_FILENO);
  Recording rows;
  {
    auto source = OpenLiveSource({"-"});
    LiveLogParser parser({}, source->source());
    SessionWriter writer(dir.Path("session.csv"), "-");
    std::string bytes;
    while (source->Read(&bytes, 0.05)) {
      parser.Feed(bytes, &rows);
      bytes.clear();
      writer.Write(parser.TakeSessionText());
    }
    parser.Finish(&rows);
    writer.Write(parser.TakeSessionText());
    EXPECT_TRUE(writer.Close());
  }
  ::dup2(saved, STDIN_FILENO);
  ::close(saved);
  EXPECT_EQ(::pclose(pipe), 0);
  ASSERT_EQ(rows.size(), whole.size());
  ASSERT_EQ(rows.gyro_radps.size(), whole.size());
  EXPECT_EQ(rows.time_s, whole.time_s);
  EXPECT_EQ(rows.accel, whole.accel);
  EXPECT_EQ(rows.gyro_radps, whole.gyro_radps);
  EXPECT_EQ(testing::ReadFile(dir.Path("session.csv")),
            testing::ReadFile(dir.Path("whole.csv")));
}

TEST(LiveSource, AStreamThatStopsIsAnErrorWithinTheTimeout) {
  StdinPipe pipe;
  LiveSourceOptions options{"-"};
  options.timeout_s = 0.3;
  auto source = OpenLiveSource(options);
  WriteAll(pipe.write_fd(), ImuLines(5));
  std::string got;
  ASSERT_TRUE(source->Read(&got, 1.0));
  EXPECT_EQ(got, ImuLines(5));
  const auto last_byte = Clock::now();
  try {
    while (source->Read(&got, 10.0)) {  // waits longer than the timeout: bounded by it
    }
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const double waited = std::chrono::duration<double>(Clock::now() - last_byte).count();
    EXPECT_GE(waited, 0.3);
    EXPECT_LT(waited, 0.3 + 0.5);
    EXPECT_EQ(e.kind(), ErrorKind::kIo);
    EXPECT_THAT(e.what(), HasSubstr("<stdin>: the stream stopped: no byte for 0.3 s"));
  }
}

// A listening socket on the loopback, an ephemeral port.
int Listen(int type, int* port) {
  const int fd = ::socket(AF_INET, type, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
  socklen_t len = sizeof(a);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  *port = ntohs(a.sin_port);
  if (type == SOCK_STREAM) ::listen(fd, 1);
  return fd;
}

TEST(LiveSource, TcpOnTheLoopbackToThePeerClosing) {
  int port = 0;
  const int server = Listen(SOCK_STREAM, &port);
  const std::string text = ImuLines(500);
  std::thread logger([&] {
    const int client = ::accept(server, nullptr, nullptr);
    SendPaced(client, text);
    ::close(client);
  });
  auto source = OpenLiveSource({fmt::format("tcp:127.0.0.1:{}", port)});
  EXPECT_EQ(source->source(), fmt::format("tcp:127.0.0.1:{}", port));
  const std::string got = Drain(source.get());
  logger.join();
  ::close(server);
  EXPECT_EQ(got, text);
  // "localhost" resolves; IPv6's bracketed form parses.
  EXPECT_EQ(KindOfLiveSource("tcp:[::1]:5000"), LiveSourceKind::kTcp);
}

TEST(LiveSource, TcpThatGoesSilentIsAnErrorWithinTheTimeout) {
  int port = 0;
  const int server = Listen(SOCK_STREAM, &port);
  int client = -1;
  std::thread logger([&] {
    client = ::accept(server, nullptr, nullptr);
    WriteAll(client, ImuLines(3));  // then silent, the connection open
  });
  LiveSourceOptions options{fmt::format("tcp:localhost:{}", port)};
  options.timeout_s = 0.25;
  auto source = OpenLiveSource(options);
  logger.join();
  std::string got;
  const auto start = Clock::now();
  EXPECT_THAT([&] { Drain(source.get()); },
              ::testing::ThrowsMessage<Error>(HasSubstr("the stream stopped")));
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 0.25 + 0.5);
  ::close(client);
  ::close(server);
}

TEST(LiveSource, TcpRefusedOrMalformedSaysWhatToDo) {
  int port = 0;
  const int closed = Listen(SOCK_DGRAM, &port);  // a port nobody listens on (TCP)
  EXPECT_THAT([&] { OpenLiveSource({fmt::format("tcp:127.0.0.1:{}", port)}); },
              ::testing::ThrowsMessage<Error>(HasSubstr(
                  fmt::format("connection refused: nothing listens on port {}", port))));
  ::close(closed);
  EXPECT_THAT([] { OpenLiveSource({"tcp:127.0.0.1"}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("expected a port number")));
  EXPECT_THAT([] { OpenLiveSource({"tcp::5000"}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("give the host")));
  EXPECT_THAT([] { OpenLiveSource({"tcp:no-such-host.invalid:5000"}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("cannot find the host")));
  LiveSourceOptions zero{"-"};
  zero.timeout_s = 0.0;
  EXPECT_THAT([&] { OpenLiveSource(zero); },
              ::testing::ThrowsMessage<Error>(HasSubstr("timeout_s must be a positive")));
}

TEST(LiveSource, UdpDatagramsHoldWholeLines) {
  auto source = OpenLiveSource({"udp:127.0.0.1:0"});
  const std::string name = source->source();
  ASSERT_THAT(name, ::testing::StartsWith("udp:127.0.0.1:"));
  const int port = std::stoi(name.substr(name.rfind(':') + 1));
  ASSERT_GT(port, 0);
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  auto send = [&](const std::string& d) {
    ::sendto(sender, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to));
  };
  send(ImuLines(2));     // two lines in one datagram
  send("0.02,0,0,9.8");  // a line without its end: given one
  send(ImuLines(1, 3));
  const std::string want = ImuLines(2) + "0.02,0,0,9.8\n" + ImuLines(1, 3);
  const std::string got = Drain(source.get(), want.size());
  EXPECT_EQ(got, want);
  ::close(sender);
  // Nothing more: the timeout, since UDP has no end.
  LiveSourceOptions quiet{"udp:127.0.0.1:0"};
  quiet.timeout_s = 0.2;
  auto silent = OpenLiveSource(quiet);
  EXPECT_THAT([&] { Drain(silent.get()); },
              ::testing::ThrowsMessage<Error>(HasSubstr("the stream stopped")));
}

TEST(LiveSource, UdpOnEveryAddressHearsAnIpv4Sender) {
  auto source = OpenLiveSource({"udp:0"});
  const std::string name = source->source();
  const int port = std::stoi(name.substr(name.rfind(':') + 1));
  ASSERT_GT(port, 0);
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const std::string lines = ImuLines(3);
  ::sendto(sender,
           lines.data(),
           lines.size(),
           0,
           reinterpret_cast<sockaddr*>(&to),
           sizeof(to));
  EXPECT_EQ(Drain(source.get(), lines.size()), lines);
  ::close(sender);
}

TEST(LiveSource, UdpPortInUseIsRefused) {
  int port = 0;
  const int taken = Listen(SOCK_DGRAM, &port);
  EXPECT_THAT([&] { OpenLiveSource({fmt::format("udp:127.0.0.1:{}", port)}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("is in use by another program")));
  ::close(taken);
}

// A pseudo-terminal pair: the master end is the sensor, the slave's path
// is opened as a serial port.
struct Pty {
  Pty() {
    char name[256];
    EXPECT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
    path = name;
  }
  ~Pty() {
    if (master >= 0) ::close(master);
    if (slave >= 0) ::close(slave);
  }
  int master = -1;
  int slave = -1;
  std::string path;
};

TEST(LiveSource, APseudoTerminalAsASerialPortWithBootTextAndACutLine) {
  Pty pty;
  LiveSourceOptions options{pty.path};
  options.baud = 115200;
  auto source = OpenLiveSource(options);
  EXPECT_EQ(source->source(), pty.path);
  ::close(pty.slave);  // the source has its own descriptor
  pty.slave = -1;
  // A board reset when its port opened: the tail of a line, noise, boot
  // text, then its lines.
  const std::string text =
      "02,0.001,0.002,0.003\n" + std::string("\xf8\x00\xfe\r\n", 5) +
      "Initializing I2C devices...\r\nMPU6050 connection successful\r\n" + ImuLines(200);
  std::thread sensor([&] {
    SendPaced(pty.master, text);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ::close(pty.master);  // unplugged
    pty.master = -1;
  });
  LiveLogParser parser({}, source->source());
  Recording rows;
  std::string bytes;
  while (source->Read(&bytes, 0.05)) {
    parser.Feed(bytes, &rows);
    bytes.clear();
  }
  sensor.join();
  parser.Finish(&rows);
  EXPECT_EQ(parser.skipped_lines(), 4u);
  ASSERT_EQ(rows.size(), 200u);
  EXPECT_NEAR(rows.time_s[199], 1.99, 1e-12);
  EXPECT_NEAR(rows.accel[0].z(), 9.81, 1e-12);
  EXPECT_NEAR(rows.accel[5].y(), -0.02, 1e-12);
}

TEST(LiveSource, SerialPortsThatCannotBeOpenedSaySo) {
  EXPECT_THAT([] { OpenLiveSource({"/dev/ttyUSB_mpcal_absent"}); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("serial port /dev/ttyUSB_mpcal_absent: no such port")));
  EXPECT_THAT([] { OpenLiveSource({"/etc/hostname"}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("is a file, not a serial port")));
  Pty pty;
  auto first = OpenLiveSource({pty.path});
  EXPECT_THAT(
      [&] { OpenLiveSource({pty.path}); },
      ::testing::ThrowsMessage<Error>(HasSubstr("busy: another program has it open")));
  Pty other;
  LiveSourceOptions odd{other.path};
  odd.baud = 12345;
  EXPECT_THAT([&] { OpenLiveSource(odd); },
              ::testing::ThrowsMessage<Error>(HasSubstr("refuses 12345 baud")));
}

}  // namespace
}  // namespace mpcal
