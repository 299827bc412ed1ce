// The shape of a subcommand: each `*_command.cc` adds itself to the root app
// and sets a callback that runs the one library call it stands for.
#pragma once

#include <CLI/CLI.hpp>

namespace mpcal::cli {

/// Thrown by a subcommand that finished normally but must exit non-zero
/// (e.g. `detect` on a session that is not good enough to calibrate).
struct ExitCode {
  int code;
};

// One per subcommand, in the order `mpcal --help` lists them.
void AddCalibrateCommand(CLI::App& root);
void AddDetectCommand(CLI::App& root);
void AddApplyCommand(CLI::App& root);
void AddRepeatCommand(CLI::App& root);
void AddVerifyCommand(CLI::App& root);
void AddSimulateCommand(CLI::App& root);
/// `simulate walk`, added under the `simulate` parent by AddSimulateCommand.
void AddSimulateWalkCommand(CLI::App& simulate);
/// `simulate noise`, likewise (simulate_noise_command.cc).
void AddSimulateNoiseCommand(CLI::App& simulate);
void AddReportCommand(CLI::App& root);
void AddDemoCommand(CLI::App& root);
void AddNoiseCommand(CLI::App& root);
void AddInspectCommand(CLI::App& root);
void AddExportCommand(CLI::App& root);
void AddImportCommand(CLI::App& root);
void AddRecordCommand(CLI::App& root);

}  // namespace mpcal::cli
