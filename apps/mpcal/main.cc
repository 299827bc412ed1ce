// mpcal: field calibration of MEMS accelerometers. Dispatches to the
// subcommands and turns every failure into one line on stderr and an exit
// code: 1 for bad input or I/O, 2 for usage.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "command.h"
#include "mpcal/error.h"

namespace {

void PrintError(const std::string& message) {
  // One line, always: multi-line messages would break scripts that grep it.
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::fflush(stdout);
  fmt::print(stderr, "mpcal: error: {}\n", line);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "mpcal: field calibration of MEMS accelerometers by the multi-position method.\n"
      "Hold the sensor still in ~26 orientations; gravity's magnitude is the only reference.",
      "mpcal"};
  app.set_version_flag("--version", std::string("mpcal ") + MPCAL_VERSION);
  app.require_subcommand(1);
  app.footer("Run 'mpcal SUBCOMMAND --help' for the options and an example of each.");
  mpcal::cli::AddCalibrateCommand(app);
  mpcal::cli::AddDetectCommand(app);
  mpcal::cli::AddApplyCommand(app);
  mpcal::cli::AddRepeatCommand(app);
  mpcal::cli::AddVerifyCommand(app);
  mpcal::cli::AddSimulateCommand(app);
  mpcal::cli::AddReportCommand(app);
  mpcal::cli::AddDemoCommand(app);
  mpcal::cli::AddNoiseCommand(app);

  // Bare `mpcal`: the help, then the error; an unknown word: say so. (CLI11
  // says "A subcommand is required" to both.)
  const CLI::App& root = app;
  std::string names;
  for (const CLI::App* sub : root.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  if (argc < 2) {
    fmt::print("{}", app.help());
    PrintError(fmt::format("no subcommand given: one of {}", names));
    return 2;
  }
  if (const std::string word = argv[1];
      !word.empty() && word.front() != '-' && root.get_subcommands([&](const CLI::App* sub) {
        return sub->check_name(word);
      }).empty()) {
    PrintError(fmt::format(
        "'{}' is not an mpcal subcommand; the subcommands are {} (run 'mpcal --help')", word,
        names));
    return 2;
  }

  try {
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
    PrintError(e.what());
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
