// mpcal: field calibration of MEMS accelerometers. Dispatches to the
// subcommands and turns every failure into one line on stderr and an exit
// code: 1 for bad input or I/O, 2 for usage.
#include <fcntl.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "calibration_table.h"
#include "colour.h"
#include "command.h"
#include "explain.h"
#include "mpcal/error.h"
#include "reference.h"
#include "version.h"

namespace {

void PrintError(const std::string& message) {
  // One line, always: multi-line messages would break scripts that grep it.
  // Warnings held back are not printed; the first, often the cause, goes
  // into the line.
  const std::vector<std::string> warnings = mpcal::cli::TakeHeldWarnings();
  std::string line = message;
  if (!warnings.empty()) {
    line += fmt::format(" (after {}: {})",
                        warnings.size() == 1
                            ? std::string("a warning")
                            : fmt::format("{} warnings, the first", warnings.size()),
                        warnings.front());
  }
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::fflush(stdout);
  fmt::print(stderr,
             "{} {}\n",
             mpcal::cli::Paint(stderr, "mpcal: error:", mpcal::cli::Tint::kDoNotUse),
             line);
}

// A standard descriptor that was closed (`>&-`) would be taken by the next
// file mpcal opens, and the table meant for the terminal would land in an
// output file. Each closed one is held by /dev/null instead; returns whether
// standard output was closed.
bool HoldClosedStandardDescriptors() {
  bool stdout_closed = false;
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) >= 0) continue;
    if (fd == STDOUT_FILENO) stdout_closed = true;
    const int held = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
    if (held >= 0 && held != fd) ::close(held);
  }
  return stdout_closed;
}

// What coreutils' close_stdout does: a table or a file written to standard
// output that did not reach it (a full disk, /dev/full, a closed pipe) is a
// failure, not a success. Returns the exit code.
int CloseStdout(int code) {
  errno = 0;
  const bool flush_failed = std::fflush(stdout) != 0;
  const int err = errno;
  // A command that failed has said so in its one line already.
  if (code != 0 || (!flush_failed && std::ferror(stdout) == 0)) return code;
  std::clearerr(stdout);
  PrintError(flush_failed && err != 0
                 ? fmt::format("error writing to standard output: {}", std::strerror(err))
                 : std::string("error writing to standard output"));
  return 1;
}

// A command's stages allocate and free arrays of a recording's size one
// after another (the reader's chunks, the samples, detection's statistic,
// the fits' residuals). glibc gives each array above 128 KiB its own mapping
// and returns it on free, so the next stage faults in fresh pages again, and
// trims the heap's top as soon as 128 KiB are free. Kept in the heap up to
// 32 MiB an array (glibc's largest mapping threshold) and up to 256 MiB of
// free top, they are reused: on the Xsens recording, calibrate of both
// sensors faults 2,900 pages instead of 3,900 and takes 76 ms of CPU instead
// of 93 (`perf stat -r 20`; bench/gyro_speed_bench.sh).
void ReuseFreedMemory() {
#ifdef M_MMAP_THRESHOLD
  ::mallopt(M_MMAP_THRESHOLD, 32 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

int Run(int argc, char** argv);

struct Subcommand {
  std::string_view name;  // as the subcommand's Add function names it
  void (*add)(CLI::App& root);
};

// In the order `mpcal --help` lists them.
constexpr Subcommand kSubcommands[] = {
    {"calibrate", mpcal::cli::AddCalibrateCommand},
    {"detect", mpcal::cli::AddDetectCommand},
    {"apply", mpcal::cli::AddApplyCommand},
    {"repeat", mpcal::cli::AddRepeatCommand},
    {"verify", mpcal::cli::AddVerifyCommand},
    {"simulate", mpcal::cli::AddSimulateCommand},
    {"report", mpcal::cli::AddReportCommand},
    {"demo", mpcal::cli::AddDemoCommand},
    {"noise", mpcal::cli::AddNoiseCommand},
    {"inspect", mpcal::cli::AddInspectCommand},
    {"export", mpcal::cli::AddExportCommand},
    {"import", mpcal::cli::AddImportCommand},
    {"record", mpcal::cli::AddRecordCommand},
};

}  // namespace

int main(int argc, char** argv) {
  ReuseFreedMemory();
  try {
    if (HoldClosedStandardDescriptors()) {
      PrintError("standard output is closed; redirect it to a file or to /dev/null");
      return 1;
    }
    const int code = Run(argc, argv);
    if (code == 0) mpcal::cli::FlushWarnings();
    return CloseStdout(code);
  } catch (...) {
    // Printing the error itself failed (no memory left to format it): the
    // exit code is all that can still be said.
    return 1;
  }
}

namespace {

int Run(int argc, char** argv) {
  CLI::App app{
      "mpcal: field calibration of MEMS accelerometers by the multi-position method.\n"
      "Hold the sensor still in ~26 orientations; gravity's magnitude is the only "
      "reference.",
      "mpcal"};
  app.set_version_flag("--version", mpcal::cli::VersionLine());
  app.require_subcommand(1);
  app.footer("Run 'mpcal SUBCOMMAND --help' for the options and an example of each.");
  // Only the subcommand named is built: each one's flags, checks and help
  // text are code and heap that a run of another would touch for nothing
  // (0.9 MiB of a short calibration's 14; docs/validation.md). The root's
  // help, the man pages and the completion take them all.
  const std::string_view word = argc < 2 ? std::string_view() : std::string_view(argv[1]);
  const auto named = std::find_if(std::begin(kSubcommands),
                                  std::end(kSubcommands),
                                  [&](const Subcommand& s) { return s.name == word; });
  if (named != std::end(kSubcommands)) {
    named->add(app);
  } else {
    for (const Subcommand& s : kSubcommands) s.add(app);
  }

  // Bare `mpcal`: the help, then the error; an unknown word: say so. (CLI11
  // says "A subcommand is required" to both.)
  std::string names;
  for (const Subcommand& s : kSubcommands) {
    names += (names.empty() ? "" : ", ") + std::string(s.name);
  }
  if (argc < 2) {
    fmt::print("{}", app.help());
    PrintError(fmt::format("no subcommand given: one of {}", names));
    return 2;
  }
  if (!word.empty() && word.front() != '-' && named == std::end(kSubcommands)) {
    PrintError(fmt::format(
        "'{}' is not an mpcal subcommand; the subcommands are {} (run 'mpcal --help')",
        word,
        names));
    return 2;
  }

  try {
    // Not a flag --help lists: the build writes the man pages and the
    // completion with it (apps/mpcal/CMakeLists.txt).
    if (std::string_view(argv[1]) == "--generate") {
      return mpcal::cli::Generate(app, std::vector<std::string>(argv + 2, argv + argc));
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string sub = app.get_subcommands().empty()
                                ? std::string()
                                : " " + app.get_subcommands().front()->get_name();
    PrintError(fmt::format("{} (run 'mpcal{} --help' for usage)", e.what(), sub));
    return 2;
  } catch (const mpcal::cli::ExitCode& e) {
    return e.code;
  } catch (const mpcal::Error& e) {
    PrintError(mpcal::cli::Explain(e));
    return 1;
  } catch (const std::bad_alloc&) {
    PrintError("out of memory; the input is larger than this machine can hold");
    return 1;
  } catch (const std::exception& e) {
    PrintError(fmt::format("internal error: {} (please report it with the command line)",
                           e.what()));
    return 1;
  }
  return 0;
}

}  // namespace
