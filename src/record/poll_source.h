// A live source read through one file descriptor with poll(2): standard
// input, a TCP stream, a UDP port, a serial port. The wait, the timeout
// that says the stream stopped, and interrupted waits live here; each kind
// of source says only how it opens and how it receives. Private to
// src/record.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "mpcal/live_source.h"

namespace mpcal::record {

class PollSource : public LiveSource {
 public:
  /// `fd` is read, and closed on destruction when `owns_fd`.
  PollSource(std::string source, int fd, bool owns_fd, double timeout_s);
  ~PollSource() override;

  bool Read(std::string* out, double wait_s) override;
  const std::string& source() const override { return source_; }
  std::size_t bytes_received() const override { return received_; }

 protected:
  /// Reads what is ready on fd() and appends it to `*out`; false at the end
  /// of the stream. Called when poll says the descriptor is ready (also
  /// for a hang-up or an error). \throws mpcal::Error (kIo).
  virtual bool Receive(std::string* out);
  /// Words for the end of the timeout: what the stream is and what to check.
  virtual std::string StoppedHint() const;
  int fd() const { return fd_; }
  /// "SOURCE: what (strerror)" as an Error of kind kIo.
  [[noreturn]] void ThrowIo(const std::string& what, int error_number) const;

 private:
  [[noreturn]] void ThrowStopped(double silent_s) const;

  std::string source_;
  int fd_;
  bool owns_fd_;
  double timeout_s_;
  std::chrono::steady_clock::time_point last_byte_;
  std::size_t received_ = 0;
};

/// Seconds from `a` to `b`.
inline double SecondsBetween(std::chrono::steady_clock::time_point a,
                             std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// Milliseconds for poll(2): `s` rounded up, at least 0.
int PollMilliseconds(double s);

}  // namespace mpcal::record
