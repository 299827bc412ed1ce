// Progress of long work on a terminal: a percentage on stderr, redrawn in
// place, only when stderr is a terminal (never in pipes, files or CI logs).
#pragma once

#include <functional>
#include <string>

namespace mpcal::cli {

class TerminalProgress {
 public:
  explicit TerminalProgress(std::string label);
  ~TerminalProgress();
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  /// A callback taking the fraction done (0..1), for the library's options.
  std::function<void(double)> Callback();
  /// Clears the line.
  void Done();

 private:
  std::string label_;
  bool enabled_;
  bool shown_ = false;
  int last_percent_ = -1;
};

}  // namespace mpcal::cli
