// mpcal record: a live IMU stream in, the session file written as it
// arrives, the user guided position by position until the positions are
// enough; then, when asked, the calibration of the file as `calibrate` does.
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "calibrate_run.h"
#include "cli_options.h"
#include "command.h"
#include "explain_record.h"
#include "mpcal/atomic_file.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"
#include "mpcal/record_guide.h"
#include "mpcal/units.h"

namespace mpcal::cli {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void OnInterrupt(int /*signal*/) { g_interrupted = 1; }

struct RecordFlags {
  std::string source;
  std::string output;
  std::string calibration;
  int baud = 115200;
  double timeout_s = 5.0;
  std::vector<double> target_std;
  bool bell = false;
  LogOptions log;
  GravityFlags gravity;
  CalibrateOptions calibrate;
};

// SIGINT sets a flag (no SA_RESTART: a wait returns at once); the handler
// before is put back at the end.
class InterruptFlag {
 public:
  InterruptFlag() {
    g_interrupted = 0;
    struct sigaction sa {};
    sa.sa_handler = OnInterrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &before_);
  }
  ~InterruptFlag() { sigaction(SIGINT, &before_, nullptr); }
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;
  bool raised() const { return g_interrupted != 0; }

 private:
  struct sigaction before_ {};
};

// `q` from the keyboard: standard input in raw mode, only when it is a
// terminal and not the source; the terminal's mode put back at the end.
class QuitKey {
 public:
  explicit QuitKey(bool enabled) {
    if (!enabled || ::isatty(STDIN_FILENO) != 1) return;
    if (::tcgetattr(STDIN_FILENO, &before_) != 0) return;
    termios raw = before_;
    raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    active_ = ::tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
  }
  ~QuitKey() {
    if (active_) ::tcsetattr(STDIN_FILENO, TCSANOW, &before_);
  }
  QuitKey(const QuitKey&) = delete;
  QuitKey& operator=(const QuitKey&) = delete;
  bool pressed() const {
    if (!active_) return false;
    pollfd p{STDIN_FILENO, POLLIN, 0};
    char c = 0;
    while (::poll(&p, 1, 0) > 0 && ::read(STDIN_FILENO, &c, 1) == 1) {
      if (c == 'q' || c == 'Q') return true;
    }
    return false;
  }

 private:
  termios before_{};
  bool active_ = false;
};

GuideOptions GuideOptionsOf(const RecordFlags& f) {
  GuideOptions o;
  o.detect = f.calibrate.detect;
  o.model = f.calibrate.solve.model;
  o.gravity_mps2 = f.calibrate.solve.gravity_mps2;
  if (!f.target_std.empty()) o.target_bias_mps2 = f.target_std[0];
  if (f.target_std.size() > 1) o.target_scale = f.target_std[1];
  if (f.target_std.size() > 2) o.target_angle_rad = f.target_std[2];
  return o;
}

// The loop's state: the guide, the rows turned to SI, what the screen shows.
class Session {
 public:
  Session(const RecordFlags& f, const std::string& source_name)
      : flags_(f), guide_(GuideOptionsOf(f)), terminal_(::isatty(STDOUT_FILENO) == 1) {
    screen_.source = source_name;
    screen_.output = f.output;
  }

  bool terminal() const { return terminal_; }
  bool done() const { return guide_.Done(); }
  int positions() const { return static_cast<int>(guide_.Positions().size()); }

  // Feeds the rows to the guide; true when a position was captured.
  bool Take(Recording* rows) {
    if (rows->time_s.empty()) return false;
    const std::optional<double> scale = FixedMps2PerUnit(rows->units);
    if (!scale) {
      throw Error(
          ErrorKind::kOption,
          fmt::format("{}: the readings are raw counts; the guide needs them in g "
                      "or m/s2: record with --units g or mps2 (a logger that "
                      "prints counts: scale them in the logger)",
                      screen_.source));
    }
    std::vector<Eigen::Vector3d> accel(rows->accel);
    for (Eigen::Vector3d& a : accel) a *= *scale;
    const bool gyro = !rows->gyro_radps.empty() && rows->gyro_units == GyroUnits::kRadps;
    std::span<const Eigen::Vector3d> gyro_radps;
    if (gyro) gyro_radps = rows->gyro_radps;
    const auto events = guide_.Feed(rows->time_s, accel, gyro_radps);
    if (screen_.rows == 0) first_s_ = rows->time_s.front();
    screen_.rows += rows->time_s.size();
    screen_.span_s = rows->time_s.back() - first_s_;
    rows->time_s.clear();
    rows->accel.clear();
    rows->gyro_radps.clear();
    bool captured = false;
    for (const GuideEvent& e : events) {
      const std::string text = WordEvent(e);
      screen_.last_event = text;
      if (!terminal_) fmt::print("{}\n", text);
      if (e.kind == GuideEventKind::kCaptured) {
        captured = true;
        if (flags_.bell) fmt::print("\a");
      }
    }
    if (!terminal_ && !events.empty()) std::fflush(stdout);
    return captured;
  }

  // Redraws the live screen, at most ten times a second.
  void Draw(bool force) {
    if (!terminal_) return;
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    screen_.gravity = guide_.Gravity();
    screen_.meter = guide_.Meter();
    screen_.positions = positions();
    screen_.held = guide_.Held();
    screen_.next_target = guide_.NextTarget();
    screen_.bound = guide_.Bound();
    screen_.turns = guide_.Turns();
    screen_.done = guide_.Done();
    if (!cleared_) fmt::print("\x1b[2J");
    cleared_ = true;
    fmt::print("\x1b[H{}", DrawScreen(screen_, stdout));
    std::fflush(stdout);
  }

 private:
  const RecordFlags& flags_;
  SessionGuide guide_;
  bool terminal_ = false;
  bool cleared_ = false;
  double first_s_ = 0.0;
  RecordScreen screen_;
  std::chrono::steady_clock::time_point last_draw_{};
};

enum class Ending { kDone, kQuit, kInterrupted, kEndOfStream };

// Reads the source until done, `q`, Ctrl-C or the end of the stream; the
// session file holds every line received by then.
Ending Record(const RecordFlags& f,
              LiveSource& source,
              SessionWriter& writer,
              Session& s) {
  LiveLogParser parser(f.log, source.source());
  const InterruptFlag interrupt;
  const QuitKey quit(s.terminal() && f.source != "-");
  Recording rows;
  std::string bytes;
  auto take = [&] {
    writer.Write(parser.TakeSessionText());
    if (s.Take(&rows)) writer.Flush();
  };
  try {
    while (true) {
      if (interrupt.raised()) return Ending::kInterrupted;
      if (quit.pressed()) return Ending::kQuit;
      const bool more = source.Read(&bytes, 0.05);
      parser.Feed(bytes, &rows);
      bytes.clear();
      take();
      s.Draw(false);
      if (s.done()) return Ending::kDone;
      if (!more) {
        parser.Finish(&rows);
        take();
        return Ending::kEndOfStream;
      }
    }
  } catch (const Error&) {
    // The lines before the one refused stay in the file.
    writer.Write(parser.TakeSessionText());
    throw;
  }
}

void Run(RecordFlags& f) {
  f.calibrate.solve.gravity_mps2 = f.gravity.Resolve();
  ThrowIfInvalid(GuideOptionsOf(f).Validate(), "record");
  if (!f.calibration.empty()) CheckOutput(f.calibration, {f.source, f.output});
  if (f.calibration == f.output) {
    throw Error(
        fmt::format("record: the session file and the calibration file are both "
                    "'{}': give the calibration another name",
                    f.output));
  }
  LiveSourceOptions so;
  so.spec = f.source;
  so.baud = f.baud;
  so.timeout_s = f.timeout_s;
  ThrowIfInvalid(so.Validate(), "record");
  SessionWriter writer(f.output, f.source);
  const std::unique_ptr<LiveSource> source = OpenLiveSource(so);
  Session s(f, source->source());
  Ending ending = Ending::kEndOfStream;
  try {
    ending = Record(f, *source, writer, s);
  } catch (const Error&) {
    writer.Close();
    throw;
  }
  s.Draw(true);
  const bool written = writer.Close();
  static constexpr const char* kWhy[] = {"done: every parameter within its target",
                                         "stopped (q)",
                                         "stopped (Ctrl-C)",
                                         "the stream ended"};
  fmt::print(
      "{}; {} captured; {}\n",
      kWhy[static_cast<int>(ending)],
      Count(static_cast<std::size_t>(s.positions()), "position"),
      written ? "session written to " + f.output : "nothing received, no session file");
  std::fflush(stdout);
  if (f.calibration.empty() || !written) return;
  fmt::print("\n");
  CalibrateFlags c;
  c.input = f.output;
  c.output = f.calibration;
  c.log = f.log;
  c.gravity = f.gravity;
  c.calibrate = f.calibrate;
  RunCalibrate(c);
}

}  // namespace

void AddRecordCommand(CLI::App& root) {
  auto flags = std::make_shared<RecordFlags>();
  CLI::App* app = root.add_subcommand(
      "record",
      "Record a session live from the sensor (serial port, standard input, TCP or UDP), "
      "writing it as it arrives and saying which orientation to hold next, until the "
      "positions determine every parameter; then optionally calibrate it");
  app->add_option("SOURCE",
                  flags->source,
                  "'-' standard input, a serial port (/dev/ttyUSB0), tcp:HOST:PORT or "
                  "udp:PORT")
      ->check(InputPath)
      ->required();
  app->add_option(
         "-o,--output", flags->output, "Session file to write (the lines as received)")
      ->check(OutputPath)
      ->required();
  app->add_option("--calibrate",
                  flags->calibration,
                  "At the end, calibrate the session as 'mpcal calibrate' does and write "
                  "this calibration file")
      ->check(OutputPath);
  app->add_option("--baud", flags->baud, "Serial port: baud rate (8N1)")
      ->capture_default_str()
      ->check(PositiveNumber);
  app->add_option("--timeout",
                  flags->timeout_s,
                  "Stop with an error when nothing arrives for this long (s)")
      ->capture_default_str()
      ->check(PositiveNumber);
  app->add_option("--target-std",
                  flags->target_std,
                  "Target 1σ of the biases (m/s2), scale-factor errors and angles (rad), "
                  "e.g. 0.002,2e-4,2e-4; default: 1.5 times what the 26 cube positions "
                  "give at the measured noise and hold")
      ->delimiter(',')
      ->expected(1, 3)
      ->check(PositiveNumber);
  app->add_flag(
      "--bell", flags->bell, "Ring the terminal's bell at every captured position");
  AddLogOptions(*app, flags->log);
  AddGravityOptions(*app, flags->gravity);
  AddCalibrateOptions(*app, flags->calibrate);
  app->footer(
      "Examples:\n"
      "  mpcal record /dev/ttyUSB0 --baud 115200 -o session.csv --calibrate calib.json\n"
      "  mpcal simulate static --realtime | mpcal record - -o session.csv\n"
      "  mpcal record tcp:192.168.1.20:5000 -o session.csv --units g\n\n"
      "On a terminal the screen is redrawn in place: where gravity points now among the "
      "26 cube directions, how still the sensor is, the positions held and the next; q "
      "or Ctrl-C stops. Otherwise one line per event. The session file is complete "
      "whenever it stops.");
  app->callback([flags] { Run(*flags); });
}

}  // namespace mpcal::cli
