#include "progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace mpcal::cli {

TerminalProgress::TerminalProgress(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) == 1) {}

TerminalProgress::~TerminalProgress() { Done(); }

std::function<void(double)> TerminalProgress::Callback() {
  if (!enabled_) return {};
  return [this](double fraction) {
    const int percent = static_cast<int>(fraction * 100.0);
    if (percent == last_percent_) return;
    last_percent_ = percent;
    shown_ = true;
    fmt::print(stderr, "\r{} {:3d}%", label_, percent);
    std::fflush(stderr);
  };
}

void TerminalProgress::Done() {
  if (!shown_) return;
  shown_ = false;
  // Erase the line so that the results start on a clean one.
  fmt::print(stderr, "\r{:{}}\r", "", label_.size() + 6);
  std::fflush(stderr);
}

}  // namespace mpcal::cli
