// mpcal repeat: several sessions of one device (recordings or calibration
// files) in, the paper's repeatability table and the verdict out.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "calibration_table.h"
#include "cli_options.h"
#include "colour.h"
#include "command.h"
#include "explain_repeat.h"
#include "gyro_table.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/repeat.h"
#include "mpcal/repeatability_file.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

struct RepeatFlags {
  std::vector<std::string> inputs;
  std::string json;
  std::string csv;
  LogOptions log;
  GravityFlags gravity;
  CalibrateOptions calibrate;
  RepeatabilityOptions repeat;
  bool verbose = false;
};

// A calibration file is JSON (an object); a log never starts with '{'.
bool IsCalibrationFile(const std::string& path) {
  if (path == "-") return false;
  // By its name too, so that a missing or broken .json is reported as a
  // calibration file, not as a log.
  if (path.ends_with(".json")) return true;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c)) {
    const auto u = static_cast<unsigned char>(c);
    // Skip white space and a UTF-8 byte-order mark.
    if (u == ' ' || u == '\t' || u == '\r' || u == '\n' || u == 0xEF || u == 0xBB ||
        u == 0xBF) {
      continue;
    }
    return c == '{';
  }
  return false;
}

// A pipe or a process substitution (`<(cat a.csv)`) can be read only once,
// but repeat looks at each input twice: is it a calibration file, then read
// it. Such an input is first copied to an unnamed temporary file, read from
// there by its /proc/self/fd name.
class SpooledInput {
 public:
  explicit SpooledInput(const std::string& path) : path_(path), readable_(path) {
    struct stat st {};
    if (path == "-" || ::stat(path.c_str(), &st) != 0 || !S_ISFIFO(st.st_mode)) return;
    const int in = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) return;  // the reader says why
    spool_ = std::tmpfile();
    if (spool_ == nullptr) {
      ::close(in);
      throw Error(fmt::format("cannot read '{}': no room for a temporary copy ({})",
                              path,
                              std::strerror(errno)));
    }
    Copy(in);
    ::close(in);
    std::fflush(spool_);
    readable_ = fmt::format("/proc/self/fd/{}", ::fileno(spool_));
  }
  ~SpooledInput() {
    if (spool_ != nullptr) std::fclose(spool_);
  }
  SpooledInput(const SpooledInput&) = delete;
  SpooledInput& operator=(const SpooledInput&) = delete;

  /// The name to open (the copy's, for a pipe).
  const std::string& readable() const { return readable_; }
  /// `message` with the copy's name replaced by the name the user gave.
  std::string Restore(std::string message) const {
    if (readable_ == path_) return message;
    for (auto at = message.find(readable_); at != std::string::npos;
         at = message.find(readable_, at + path_.size())) {
      message.replace(at, readable_.size(), path_);
    }
    return message;
  }

 private:
  void Copy(int in) {
    std::vector<char> buffer(std::size_t{1} << 16);
    bool first = true;
    while (true) {
      const ssize_t n = ::read(in, buffer.data(), buffer.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      const auto size = static_cast<std::size_t>(n);
      if (std::fwrite(buffer.data(), 1, size, spool_) != size) {
        throw Error(fmt::format("cannot read '{}': the temporary copy failed ({})",
                                path_,
                                std::strerror(errno)));
      }
      // Binary data (a pipe from /dev/urandom) is not copied to the end:
      // the first bytes are enough for the reader to refuse it.
      if (first && std::memchr(buffer.data(), '\0', size) != nullptr) break;
      first = false;
    }
  }

  std::string path_;
  std::string readable_;
  std::FILE* spool_ = nullptr;
};

// `path` is read; `name`, the input as the user gave it, is in messages.
Calibration CalibrateSession(const std::string& path,
                             const std::string& name,
                             RepeatFlags& f) {
  TerminalProgress progress("reading " + name);
  f.log.progress = progress.Callback();
  const Recording recording = ReadLog(path, f.log);
  progress.Done();
  PrintWarnings(recording.warnings);
  // Among several sessions, say which one cannot be calibrated.
  const CalibrateResult result = [&] {
    try {
      return CalibrateRecording(recording, f.calibrate);
    } catch (const Error& e) {
      if (std::string_view(e.what()).starts_with(path)) throw;
      throw Error(e.kind(), fmt::format("{}: {}", name, e.what()), e.advice());
    }
  }();
  for (const std::string& w : result.warnings)
    PrintWarnings({fmt::format("{}: {}", name, w)});
  if (!result.solve.converged()) {
    throw Error(
        fmt::format("{}: the fit did not converge ({}); check the positions with "
                    "'mpcal detect {}'",
                    name,
                    result.solve.message,
                    name));
  }
  if (f.verbose) {
    fmt::print("  {}: calibrated, {} positions, residual RMS {:.2g} m/s2\n",
               name,
               result.positions.size(),
               result.solve.residual_rms_after_mps2);
  }
  return result.calibration;
}

// Whether one calibration serves every session, from each parameter's test
// between the sessions: good when none changed beyond its 1σ, look at when
// only the bias did (as it does at each power-up) or nothing could be
// tested, do not use when a scale-factor error or non-orthogonality did.
void PrintOneCalibrationVerdict(const RepeatabilityResult& result) {
  bool bias_changed = false, other_changed = false, tested = false;
  for (int p = 0; p < kNumModelParameters; ++p) {
    const auto& changed = result.parameters[static_cast<std::size_t>(p)].changed;
    if (!changed) continue;
    tested = true;
    if (*changed) (p < 3 ? bias_changed : other_changed) = true;
  }
  const Verdict verdict = other_changed             ? Verdict::kDoNotUse
                          : bias_changed || !tested ? Verdict::kLookAt
                                                    : Verdict::kGood;
  const char* why =
      other_changed  ? "a scale-factor error or non-orthogonality changed between the "
                       "sessions: one calibration does not serve them all"
      : bias_changed ? "one calibration serves the sessions but for the bias, which "
                       "changes at each power-up"
      : tested       ? "one calibration serves every session"
                     : "no 1σ to judge the sessions by";
  fmt::print("verdict: {}: {}\n", PaintVerdict(stdout, verdict), why);
}

void Run(RepeatFlags& f) {
  if (!f.json.empty() && !f.csv.empty()) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::weakly_canonical(fs::absolute(f.json, ec), ec) ==
        fs::weakly_canonical(fs::absolute(f.csv, ec), ec)) {
      throw Error(fmt::format(
          "--json and --csv both name '{}': one would overwrite the other; give each its "
          "own file",
          f.json));
    }
  }
  for (const std::string& out : {f.json, f.csv}) {
    if (!out.empty()) CheckOutput(out, f.inputs);
  }
  f.calibrate.solve.gravity_mps2 = f.gravity.Resolve();
  ThrowIfInvalid(f.calibrate.Validate(), "repeat");
  ThrowIfInvalid(f.repeat.Validate(), "repeat");
  if (f.inputs.size() < 2) {
    throw Error(fmt::format(
        "repeatability needs at least 2 sessions of the device, got {}: give two or more "
        "recordings or calibration files",
        f.inputs.size()));
  }

  std::vector<Calibration> trials;
  if (f.verbose) fmt::print("{} sessions:\n", f.inputs.size());
  for (const std::string& path : f.inputs) {
    const SpooledInput input(path);
    try {
      if (IsCalibrationFile(input.readable())) {
        trials.push_back(ReadCalibrationFile(input.readable()));
        if (f.verbose) {
          fmt::print(
              "  {}: calibration file{}\n", path, trials.back().std ? "" : " (no 1σ)");
        }
      } else {
        trials.push_back(CalibrateSession(input.readable(), path, f));
      }
    } catch (const Error& e) {
      throw Error(e.kind(), input.Restore(e.what()), e.advice());
    }
  }
  if (f.verbose) fmt::print("\n");

  const RepeatabilityResult result = [&] {
    try {
      return AnalyzeRepeatability(trials, f.inputs, f.repeat);
    } catch (const Error& e) {
      throw Error(e.kind(), ExplainRepeatRefusal(e));
    }
  }();
  fmt::print("{}\n{}", FormatRepeatabilityTable(result), RepeatabilityVerdict(result));
  PrintOneCalibrationVerdict(result);
  fmt::print("{}", FormatGyroRepeatTable(trials, f.inputs));  // IMU trials (gyro_table.h)
  for (const std::string& note : result.notes) fmt::print("note: {}\n", note);
  if (!f.json.empty()) {
    WriteFileAtomically(f.json, RepeatabilityToJson(result));
    fmt::print("wrote {}\n", f.json);
  }
  if (!f.csv.empty()) {
    WriteFileAtomically(f.csv, RepeatabilityToCsv(result));
    fmt::print("wrote {}\n", f.csv);
  }
}

}  // namespace

void AddRepeatCommand(CLI::App& root) {
  auto flags = std::make_shared<RepeatFlags>();
  CLI::App* app = root.add_subcommand(
      "repeat",
      "Repeatability across sessions (the paper's Tables 4-6): each parameter per trial, "
      "mean, population and sample standard deviation, and which parameters changed "
      "between sessions beyond their 1σ: calibrate once, or before each use?");
  app->add_option("SESSION_OR_CALIB",
                  flags->inputs,
                  "Two or more sessions of one device: logs (calibrated here with the "
                  "options below) or calibration files (JSON from 'mpcal calibrate')")
      ->check(InputPath)
      ->required();
  app->add_option("--json",
                  flags->json,
                  "Write the table as JSON (mpcal.repeatability/1, SI units)")
      ->check(OutputPath);
  app->add_option("--csv", flags->csv, "Write the table as CSV (SI units)")
      ->check(OutputPath);
  app->add_option(
         "--significance",
         flags->repeat.significance,
         "Significance level of the test whether a parameter changed between "
         "sessions beyond its 1σ (chi-square of the trials around their weighted "
         "mean)")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 0.5));
  AddLogOptions(*app, flags->log);
  AddGravityOptions(*app, flags->gravity);
  AddCalibrateOptions(*app, flags->calibrate);
  app->add_flag("-v,--verbose",
                flags->verbose,
                "Also list the sessions as they are read, each log's positions and "
                "residual RMS");
  app->footer(
      "Examples:\n"
      "  mpcal repeat monday.csv tuesday.csv wednesday.csv --json repeat.json\n"
      "  mpcal repeat trial1.json trial2.json trial3.json --csv repeat.csv\n"
      "  mpcal repeat s1.csv s2.csv --units g --latitude -25.45 --height 920\n"
      "The last line says whether one calibration serves every session: good, look at "
      "or do not use, coloured on a terminal; set NO_COLOR=1 for plain text.");
  app->callback([flags] { Run(*flags); });
}

}  // namespace mpcal::cli
