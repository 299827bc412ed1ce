// A serial port (any path that is not "-", "tcp:" or "udp:"): opened through
// libserialport, raw 8N1 at the baud rate, no flow control. A port the
// system does not list as a serial device (a pseudo-terminal, as socat and
// ser2net make) is set up with termios, the same way. The port is locked
// (flock) for the session, so that two programs do not split its bytes; the
// device going away (unplugged, the other end of a pseudo-terminal closed)
// is the end of the stream.
#include <fcntl.h>
#include <libserialport.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "poll_source.h"
#include "sources.h"

namespace mpcal::record {
namespace {

[[noreturn]] void ThrowPort(const std::string& port, const std::string& what) {
  throw Error(ErrorKind::kIo, fmt::format("serial port {}: {}", port, what));
}

// What failed to open, in words and with what to do.
[[noreturn]] void ThrowOpenFailed(const std::string& port, int error_number) {
  switch (error_number) {
    case ENOENT:
    case ENODEV:
    case ENXIO:
      ThrowPort(port,
                "no such port; is the device plugged in? (the ports there are: ls "
                "/dev/ttyUSB* /dev/ttyACM*)");
    case EACCES:
    case EPERM:
      ThrowPort(port,
                "permission denied; add yourself to the group that owns it (sudo "
                "usermod -aG dialout $USER, then log in again)");
    case EBUSY:
    case EWOULDBLOCK:
      ThrowPort(port,
                "busy: another program has it open (a serial monitor, ModemManager); "
                "close that program first");
    default:
      ThrowPort(port, fmt::format("cannot be opened ({})", std::strerror(error_number)));
  }
}

[[noreturn]] void ThrowBaud(const std::string& port, int baud) {
  ThrowPort(port,
            fmt::format("refuses {} baud; give the rate the sensor sends at (115200, "
                        "230400, 460800, 921600, ...)",
                        baud));
}

speed_t SpeedOf(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1500000:
      return B1500000;
    case 2000000:
      return B2000000;
    case 3000000:
      return B3000000;
    case 4000000:
      return B4000000;
    default:
      return B0;
  }
}

class SerialSource final : public PollSource {
 public:
  SerialSource(std::string name, int fd, sp_port* port, double timeout_s)
      : PollSource(std::move(name), fd, /*owns_fd=*/port == nullptr, timeout_s),
        port_(port) {}
  ~SerialSource() override {
    if (port_ != nullptr) {
      sp_close(port_);
      sp_free_port(port_);
    }
  }

 protected:
  bool Receive(std::string* out) override {
    constexpr std::size_t kBytes = 4096;
    const std::size_t before = out->size();
    out->resize(before + kBytes);
    const ssize_t n = ::read(fd(), out->data() + before, kBytes);
    const int error_number = errno;
    out->resize(before + static_cast<std::size_t>(n > 0 ? n : 0));
    if (n > 0) return true;
    if (n == 0) return false;  // ready yet empty: hung up
    if (error_number == EINTR || error_number == EAGAIN) return true;
    // The device went away (unplugged, the other end closed): the end.
    if (error_number == EIO || error_number == ENODEV || error_number == ENXIO) {
      return false;
    }
    ThrowIo("reading failed", error_number);
  }
  std::string StoppedHint() const override {
    return "is the sensor powered and sending, and is the baud rate right?";
  }

 private:
  sp_port* port_;
};

// Raw 8N1 with termios, for a port libserialport does not list.
int OpenWithTermios(const std::string& port, int baud) {
  const speed_t speed = SpeedOf(baud);
  if (speed == B0) ThrowBaud(port, baud);
  const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) ThrowOpenFailed(port, errno);
  termios t{};
  if (::tcgetattr(fd, &t) != 0) {
    const int error_number = errno;
    ::close(fd);
    ThrowPort(port,
              fmt::format("is not a serial port ({})", std::strerror(error_number)));
  }
  ::cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~(CSTOPB | PARENB | CRTSCTS);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  if (::cfsetispeed(&t, speed) != 0 || ::cfsetospeed(&t, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &t) != 0) {
    ::close(fd);
    ThrowBaud(port, baud);
  }
  return fd;
}

// Raw 8N1 through libserialport; nullptr when it does not list the port.
sp_port* OpenWithLibserialport(const std::string& port,
                               const std::string& real,
                               int baud) {
  sp_port* p = nullptr;
  if (sp_get_port_by_name(real.c_str(), &p) != SP_OK) return nullptr;
  if (sp_open(p, SP_MODE_READ) != SP_OK) {
    const int error_number = sp_last_error_code();
    sp_free_port(p);
    ThrowOpenFailed(port, error_number);
  }
  auto fail = [&](auto&& then) {
    sp_close(p);
    sp_free_port(p);
    then();
  };
  if (sp_set_baudrate(p, baud) != SP_OK) fail([&] { ThrowBaud(port, baud); });
  if (sp_set_bits(p, 8) != SP_OK || sp_set_parity(p, SP_PARITY_NONE) != SP_OK ||
      sp_set_stopbits(p, 1) != SP_OK ||
      sp_set_flowcontrol(p, SP_FLOWCONTROL_NONE) != SP_OK) {
    const std::string why = sp_last_error_message();
    fail([&] {
      ThrowPort(port,
                "cannot be set to 8 data bits, no parity, 1 stop bit (" + why + ")");
    });
  }
  return p;
}

}  // namespace

std::unique_ptr<LiveSource> OpenSerial(const LiveSourceOptions& options) {
  const std::string& port = options.spec;
  struct stat st {};
  if (::stat(port.c_str(), &st) != 0) ThrowOpenFailed(port, errno);
  if (!S_ISCHR(st.st_mode)) {
    ThrowPort(port,
              S_ISREG(st.st_mode)
                  ? "is a file, not a serial port; a recorded log is read as a log"
                  : "is not a serial port (not a character device)");
  }
  // libserialport knows a port by its name under /dev (a link such as
  // /dev/serial/by-id/... is resolved first).
  char real[PATH_MAX];
  const std::string resolved = ::realpath(port.c_str(), real) != nullptr ? real : port;
  sp_port* p = OpenWithLibserialport(port, resolved, options.baud);
  int fd = -1;
  if (p != nullptr) {
    if (sp_get_port_handle(p, &fd) != SP_OK) {
      sp_close(p);
      sp_free_port(p);
      ThrowPort(port, "has no handle to read from");
    }
  } else {
    fd = OpenWithTermios(port, options.baud);
  }
  auto source = std::make_unique<SerialSource>(port, fd, p, options.timeout_s);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) ThrowOpenFailed(port, EBUSY);
  return source;
}

}  // namespace mpcal::record
