// mpcal noise: the Allan deviation of a still recording, the noise terms it
// supports (each with its interval), how long to record for those it does
// not, and the files filters want (JSON, Kalibr's imu.yaml).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "cli_options.h"
#include "colour.h"
#include "command.h"
#include "explain.h"
#include "explain_detect.h"
#include "explain_noise.h"
#include "mpcal/apply.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/noise.h"
#include "mpcal/noise_file.h"
#include "mpcal/noise_units.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

struct NoiseFlags {
  std::string input;
  std::string json;
  std::string kalibr;
  std::string calib;
  std::string rostopic = "/imu0";
  bool whole = false;
  LogOptions log;
  GravityFlags gravity;
  DetectOptions detect;
  NoiseOptions noise;
  // Given on the command line (else a calibration's units are taken).
  bool units_given = false;
  bool gyro_units_given = false;
  bool verbose = false;
  bool strict = false;
  double inflate = 1.0;
};

// "1 sample", "2 samples".
std::string Count(std::size_t n, const char* noun) {
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

constexpr NoiseTerm kTableTerms[] = {NoiseTerm::kQuantisation,
                                     NoiseTerm::kWhiteNoise,
                                     NoiseTerm::kBiasInstability,
                                     NoiseTerm::kRandomWalk,
                                     NoiseTerm::kRateRamp};

const char* TermLabel(NoiseTerm t, bool gyro) {
  switch (t) {
    case NoiseTerm::kQuantisation:
      return "quantisation Q";
    case NoiseTerm::kWhiteNoise:
      return gyro ? "white noise N (ARW)" : "white noise N (VRW)";
    case NoiseTerm::kBiasInstability:
      return "bias instability B";
    case NoiseTerm::kRandomWalk:
      return gyro ? "rate random walk K" : "accel. random walk K";
    case NoiseTerm::kRateRamp:
      return "rate ramp R";
  }
  return "";
}

std::string SiCell(const TermEstimate& e) {
  if (e.value) return fmt::format("{:.4g} [{:.3g}, {:.3g}]", *e.value, e.lo, e.hi);
  const char* why = e.status == TermStatus::kDisagrees ? "model misses" : "not seen";
  if (e.upper_bound > 0.0) return fmt::format("< {:.3g} ({})", e.upper_bound, why);
  return why;
}

std::string DatasheetCell(const TermEstimate& e, NoiseTerm t, bool gyro) {
  const double v = e.value ? *e.value : e.upper_bound;
  const noise_units::DatasheetValue d = noise_units::ToDatasheet(t, gyro, v);
  return fmt::format("{}{:.4g}", e.value ? "" : "< ", d.value);
}

// The cluster times a term was read from: "0.01–4.5" (s).
std::string RegionCell(bool measured, double lo_s, double hi_s) {
  return measured ? fmt::format("{:.2g}–{:.2g}", lo_s, hi_s) : std::string("—");
}

// The value of a Gauss-Markov process or sinusoid and its interval, or why
// there is none.
std::string ExtraCell(const std::optional<double>& v,
                      double lo,
                      double hi,
                      TermStatus status,
                      bool modelled) {
  if (v) return fmt::format("{:.4g} [{:.3g}, {:.3g}]", *v, lo, hi);
  if (!modelled) return "left out of the model";
  return status == TermStatus::kDisagrees ? "model misses" : "not seen";
}

// The rows of the Gauss-Markov process and the sinusoid, shown where some
// axis has one (measured, or where the model misses the curve).
void PrintExtraTerms(const SensorNoise& s, bool gyro) {
  const char* u = gyro ? "rad/s" : "m/s²";
  bool gm = false, sine = false;
  for (const AxisNoise& a : s.axes) {
    gm = gm || a.gauss_markov.status != TermStatus::kNotSeen;
    sine = sine || a.sinusoid.status != TermStatus::kNotSeen;
  }
  const auto row = [](const char* label, const char* unit) {
    fmt::print("{:<22} {:<11}", label, unit);
  };
  if (gm) {
    row("Gauss-Markov σ", u);
    for (const AxisNoise& a : s.axes) {
      const GaussMarkovTerm& g = a.gauss_markov;
      fmt::print(" {:>30}",
                 ExtraCell(g.sigma, g.sigma_lo, g.sigma_hi, g.status, g.modelled));
    }
    fmt::print("\n");
    row("  correlation time τc", "s");
    for (const AxisNoise& a : s.axes) {
      const GaussMarkovTerm& g = a.gauss_markov;
      fmt::print(
          " {:>30}",
          g.sigma ? fmt::format(
                        "{:.3g} [{:.3g}, {:.3g}]", g.tau_c_s, g.tau_c_lo_s, g.tau_c_hi_s)
                  : std::string("—"));
    }
    fmt::print("\n");
    row("  read from τ", "s");
    for (const AxisNoise& a : s.axes) {
      const GaussMarkovTerm& g = a.gauss_markov;
      fmt::print(" {:>30}", RegionCell(g.sigma.has_value(), g.tau_lo_s, g.tau_hi_s));
    }
    fmt::print("\n");
  }
  if (sine) {
    row("sinusoid amplitude A", u);
    for (const AxisNoise& a : s.axes) {
      const SinusoidTerm& n = a.sinusoid;
      fmt::print(
          " {:>30}",
          ExtraCell(n.amplitude, n.amplitude_lo, n.amplitude_hi, n.status, n.modelled));
    }
    fmt::print("\n");
    row("  period P", "s");
    for (const AxisNoise& a : s.axes) {
      const SinusoidTerm& n = a.sinusoid;
      fmt::print(
          " {:>30}",
          n.amplitude
              ? fmt::format(
                    "{:.4g} [{:.4g}, {:.4g}]", n.period_s, n.period_lo_s, n.period_hi_s)
              : std::string("—"));
    }
    fmt::print("\n");
    row("  read from τ", "s");
    for (const AxisNoise& a : s.axes) {
      const SinusoidTerm& n = a.sinusoid;
      fmt::print(" {:>30}", RegionCell(n.amplitude.has_value(), n.tau_lo_s, n.tau_hi_s));
    }
    fmt::print("\n");
  }
}

void PrintSensor(const SensorNoise& s, bool gyro) {
  fmt::print("\n{:<22} {:<11} {:>30} {:>30} {:>30}\n",
             gyro ? "gyroscope" : "accelerometer",
             "unit",
             "x",
             "y",
             "z");
  for (const NoiseTerm t : kTableTerms) {
    bool any = false;
    for (const AxisNoise& a : s.axes) any = any || a.term(t).value.has_value();
    // Quantisation and rate ramp are shown only where some axis has them.
    if (!any && (t == NoiseTerm::kQuantisation || t == NoiseTerm::kRateRamp)) continue;
    fmt::print("{:<22} {:<11}", TermLabel(t, gyro), noise_units::SiUnit(t, gyro));
    for (const AxisNoise& a : s.axes) fmt::print(" {:>30}", SiCell(a.term(t)));
    fmt::print("\n");
    const noise_units::DatasheetValue unit = noise_units::ToDatasheet(t, gyro, 1.0);
    if (unit.unit[0] == '\0') continue;
    fmt::print("{:<22} {:<11}", "", unit.unit);
    for (const AxisNoise& a : s.axes)
      fmt::print(" {:>30}", DatasheetCell(a.term(t), t, gyro));
    fmt::print("\n");
    if (!any) continue;
    fmt::print("{:<22} {:<11}", "  read from τ", "s");
    for (const AxisNoise& a : s.axes) {
      const TermEstimate& e = a.term(t);
      fmt::print(" {:>30}", RegionCell(e.value.has_value(), e.tau_lo_s, e.tau_hi_s));
    }
    fmt::print("\n");
  }
  PrintExtraTerms(s, gyro);
  fmt::print("{:<22} {:<11}", "model vs curve", "τ points");
  for (const AxisNoise& a : s.axes) fmt::print(" {:>30}", ModelCheckCell(a.check));
  fmt::print("\n");
  bool excluded = false;
  for (const AxisNoise& a : s.axes) excluded = excluded || a.check.excluded > 0;
  if (!excluded) return;
  fmt::print("{:<22} {:<11}", "fitted from τ", "s");
  for (const AxisNoise& a : s.axes)
    fmt::print(" {:>30}", fmt::format("{:.3g}", a.check.from_tau_s));
  fmt::print("\n");
}

// The findings in words: terms not measured, why, and how long to record.
void PrintFindings(const SensorNoise& s, bool gyro, const NoiseResult& r) {
  const char* sensor = gyro ? "gyroscope" : "accelerometer";
  for (const NoiseTerm t :
       {NoiseTerm::kWhiteNoise, NoiseTerm::kBiasInstability, NoiseTerm::kRandomWalk}) {
    std::vector<std::string> not_seen, masked;
    for (int i = 0; i < 3; ++i) {
      const TermEstimate& e = s.axes[i].term(t);
      const std::string axis(1, static_cast<char>('x' + i));
      if (e.status == TermStatus::kMasked) masked.push_back(axis);
      if (e.status == TermStatus::kNotSeen) not_seen.push_back(axis);
    }
    const std::optional<double> needed = s.record_needed_s[static_cast<int>(t)];
    const std::optional<double> needed_half = s.record_needed_half_s[static_cast<int>(t)];
    const std::string name = TermLabel(t, gyro);
    if (!not_seen.empty()) {
      fmt::print(
          "{} {} on {}: not measured — no stretch of the curve where it dominates in "
          "this {} record; the bound is its largest value the curve allows.",
          sensor,
          name,
          fmt::join(not_seen, ", "),
          FormatRecordLength(r.record_s));
      if (needed) {
        fmt::print(
            " To measure it, record at least {} (if it is as large as the bound; "
            "{} if half of it).",
            FormatRecordLength(*needed),
            needed_half ? FormatRecordLength(*needed_half) : std::string("longer"));
      }
      fmt::print("\n");
    }
    if (!masked.empty()) {
      fmt::print(
          "{} {} on {}: below the curve where its neighbours meet; a longer record "
          "will not show it (the bound stands).\n",
          sensor,
          name,
          fmt::join(masked, ", "));
    }
  }
}

// The axes ("x, y") of `s` on which `status_of` an axis is `status`.
template <typename StatusOf>
std::string AxesWith(const SensorNoise& s, TermStatus status, StatusOf status_of) {
  std::vector<std::string> axes;
  for (int i = 0; i < 3; ++i) {
    if (status_of(s.axes[i]) == status) axes.emplace_back(1, static_cast<char>('x' + i));
  }
  return fmt::format("{}", fmt::join(axes, ", "));
}

// Each term the model misses the curve for, with its axes: the IEEE terms,
// then the Gauss-Markov process and the sinusoid.
std::vector<std::string> TermsDisagreeing(const SensorNoise& s, bool gyro) {
  std::vector<std::string> out;
  const auto add = [&](std::string_view name, const std::string& axes) {
    if (!axes.empty()) out.push_back(fmt::format("{} on {}", name, axes));
  };
  for (const NoiseTerm t : kTableTerms) {
    add(TermLabel(t, gyro), AxesWith(s, TermStatus::kDisagrees, [t](const AxisNoise& a) {
          return a.term(t).status;
        }));
  }
  add("Gauss-Markov", AxesWith(s, TermStatus::kDisagrees, [](const AxisNoise& a) {
        return a.gauss_markov.status;
      }));
  add("sinusoid", AxesWith(s, TermStatus::kDisagrees, [](const AxisNoise& a) {
        return a.sinusoid.status;
      }));
  return out;
}

// The terms a longer record would show, with their axes; whether the white
// noise is among them; the longest record any of them needs.
struct TermsNotSeen {
  std::vector<std::string> terms;
  bool white_missing = false;
  std::optional<double> needed_s;
};

TermsNotSeen NotSeen(const SensorNoise& s, bool gyro) {
  TermsNotSeen out;
  for (const NoiseTerm t :
       {NoiseTerm::kWhiteNoise, NoiseTerm::kBiasInstability, NoiseTerm::kRandomWalk}) {
    const std::string axes = AxesWith(
        s, TermStatus::kNotSeen, [t](const AxisNoise& a) { return a.term(t).status; });
    if (axes.empty()) continue;
    if (t == NoiseTerm::kWhiteNoise) out.white_missing = true;
    out.terms.push_back(fmt::format("{} on {}", TermLabel(t, gyro), axes));
    if (const auto n = s.record_needed_s[static_cast<int>(t)]) {
      out.needed_s = std::max(out.needed_s.value_or(0.0), *n);
    }
  }
  return out;
}

// One line per sensor: good when every term is measured or masked (a
// longer record would not show it), look at when a term is not seen yet (a
// longer record would show it) or the model misses the curve, do not use
// when not even the white noise shows: the record is not still noise.
void PrintSensorVerdict(const SensorNoise& s, bool gyro, const NoiseResult& r) {
  const std::vector<std::string> disagree = TermsDisagreeing(s, gyro);
  const TermsNotSeen not_seen = NotSeen(s, gyro);
  const Verdict verdict = not_seen.white_missing ? Verdict::kDoNotUse
                          : not_seen.terms.empty() && disagree.empty() ? Verdict::kGood
                                                                       : Verdict::kLookAt;
  std::string why =
      not_seen.terms.empty()
          ? std::string("every term measured or bounded as far as any record shows it")
          : fmt::format("not measured in this {} record: {}",
                        FormatRecordLength(r.record_s),
                        fmt::join(not_seen.terms, "; "));
  if (!disagree.empty()) {
    why = fmt::format("the model misses the curve where these dominate: {}; {}",
                      fmt::join(disagree, "; "),
                      not_seen.terms.empty() ? "the rest measured or bounded" : why);
  }
  if (not_seen.needed_s)
    why += fmt::format("; record at least {} to see them (if as large as their bounds)",
                       FormatRecordLength(*not_seen.needed_s));
  fmt::print("{:<14} {} {}\n",
             gyro ? "gyroscope" : "accelerometer",
             PaintVerdict(stdout, verdict, 11),
             why);
}

// What was read and which part of it was analysed.
struct Analysis {
  NoiseResult result;
  std::size_t rows = 0;
  double span_s = 0.0;
  bool has_gyro = false;
  std::vector<std::string> warnings;
  std::string which;  // the part analysed, in words
};

// Why the stream could not take the whole record, in words.
std::string WhyNotStill(const StillVerdict& v) {
  switch (v.reason) {
    case NotStillReason::kNone:
      return "";
    case NotStillReason::kMoved:
      return fmt::format("the sensor moved near t = {:.1f} s", v.largest_at_s);
    case NotStillReason::kRangeLimit:
      return fmt::format("a reading at the range limit at t = {:.1f} s", v.gap_at_s);
    case NotStillReason::kGap:
      return fmt::format("a gap in time after t = {:.1f} s", v.gap_at_s);
    case NotStillReason::kTooShort:
      return "the record is shorter than one detection window";
    case NotStillReason::kNotFinite:
      return "a reading is not a number";
  }
  return "";
}

// The analysis of a held recording whose stream found motion: detection's
// longest still part (or its whole, when detection finds no motion).
void AnalyseDetected(const NoiseFlags& f, const Recording& rec, Analysis* a) {
  const DetectResult det = DetectStatic(rec, f.detect);
  const std::optional<NoiseSegment> segment = ChooseNoiseSegment(rec, det);
  if (!segment) {
    throw Error(
        fmt::format("{}: no still part found in {:.1f} s ({}); if the sensor was "
                    "still, give --whole to analyse all of it",
                    f.input,
                    a->span_s,
                    ExplainDetection(det.finding)));
  }
  TerminalProgress analysing("analysing");
  a->result = AnalyseNoise(rec, *segment, *FixedMps2PerUnit(rec.units), f.noise);
  analysing.Done();
  a->which = segment->kind == NoiseSegmentKind::kWholeRecord
                 ? "the whole record (detection found the sensor still throughout)"
                 : fmt::format(
                       "the longest still part, {:.1f}-{:.1f} s, of {} found by "
                       "detection (the sensor moved)",
                       rec.time_s[segment->begin] - rec.time_s.front(),
                       rec.time_s[segment->end - 1] - rec.time_s.front(),
                       segment->static_intervals);
}

// A log that can be read twice: a regular file (not standard input or a pipe).
bool CanReadTwice(const std::string& input) {
  std::error_code ec;
  return input != "-" && std::filesystem::is_regular_file(input, ec);
}

// Reads the log into the stream: a file row by row, holding none of it;
// standard input whole (it cannot be read again), kept for detection.
// With a calibration, every row is corrected to SI first.
std::optional<Recording> ReadInto(NoiseFlags& f,
                                  const RecordingCorrector* correct,
                                  NoiseStream* stream,
                                  UnitsEvidence* evidence,
                                  Analysis* a) {
  TerminalProgress progress("reading " + f.input);
  f.log.progress = progress.Callback();
  std::optional<Recording> held;
  if (CanReadTwice(f.input)) {
    const LogStreamSummary s = ReadLogRows(f.input, f.log, [&](const Recording& read) {
      const Recording corrected = correct ? (*correct)(read) : Recording{};
      const Recording& rows = correct ? corrected : read;
      evidence->Add(rows, 0, rows.size());
      stream->Add(rows);
    });
    a->rows = s.rows;
    a->span_s = s.last_time_s - s.first_time_s;
    a->warnings = s.warnings;
  } else {
    held = ReadLog(f.input, f.log);
    if (correct) held = (*correct)(*held);
    *evidence = UnitsEvidence::Of(*held);
    stream->Add(*held);
    a->rows = held->size();
    a->span_s = held->time_s.back() - held->time_s.front();
    a->warnings = held->warnings;
  }
  progress.Done();
  f.log.progress = nullptr;
  a->has_gyro = stream->has_gyro();
  return held;
}

// Reads and analyses: the whole record from the stream when the sensor never
// moved (or with --whole); else detection's longest still part, from the
// log read again.
Analysis Analyse(NoiseFlags& f, const RecordingCorrector* correct) {
  Analysis a;
  const AccelUnits units = correct ? AccelUnits::kMps2 : f.log.units;
  NoiseStream stream(f.noise, f.whole ? nullptr : &f.detect, units);
  UnitsEvidence evidence;
  std::optional<Recording> held = ReadInto(f, correct, &stream, &evidence, &a);
  WithDetectWords([&] { CheckUnits(evidence, f.gravity.Resolve()); });
  if (!f.kalibr.empty() && !a.has_gyro) {
    throw Error(f.input +
                ": Kalibr's imu.yaml needs the gyroscope, and the log has none "
                "(give its columns with --columns ...,gx=..,gy=..,gz=..)");
  }
  const std::optional<StillVerdict> still = stream.Stillness();
  if (!still || still->still) {
    const NoiseSegment whole{NoiseSegmentKind::kWholeRecord, 0, stream.rows(), 1};
    a.result = stream.Finish(*FixedMps2PerUnit(units), whole);
    a.which = still ? "the whole record (detection found the sensor still throughout)"
                    : "the whole record (--whole: detection not run)";
    return a;
  }
  fmt::print("  note: {}: finding its longest still part{}\n",
             WhyNotStill(*still),
             held ? "" : " (reading the log again)");
  if (!held) {
    TerminalProgress progress("reading " + f.input + " again");
    f.log.progress = progress.Callback();
    held = ReadLog(f.input, f.log);
    if (correct) held = (*correct)(*held);
    progress.Done();
  }
  AnalyseDetected(f, *held, &a);
  return a;
}

// The JSON and Kalibr files asked for, and a warning for each Kalibr value
// that is a bound rather than a measurement. Both texts are made before
// either is written, and a file written is removed again when the next one
// fails, so that a failing command leaves no file behind.
void WriteFiles(const NoiseFlags& f, const NoiseResult& r) {
  const std::string json =
      f.json.empty() ? "" : NoiseJson(r, f.input, f.noise.allan.confidence);
  const std::optional<KalibrFile> k =
      f.kalibr.empty()
          ? std::nullopt
          : std::optional<KalibrFile>(KalibrYaml(r, f.input, f.rostopic, f.inflate));
  if (k && f.strict) {
    std::vector<std::string> bounds;
    for (const auto& [name, v] :
         {std::pair{"accelerometer_noise_density", k->accel_noise_density},
          std::pair{"accelerometer_random_walk", k->accel_random_walk},
          std::pair{"gyroscope_noise_density", k->gyro_noise_density},
          std::pair{"gyroscope_random_walk", k->gyro_random_walk}}) {
      if (v.upper_bound) bounds.emplace_back(name);
    }
    if (!bounds.empty()) {
      throw Error(fmt::format(
          "{}: --strict: {} not measured on any axis (only an upper bound); record "
          "longer, or leave out --strict to write the bounds, marked",
          f.kalibr,
          fmt::join(bounds, ", ")));
    }
  }
  std::error_code ec;
  const bool json_existed = !f.json.empty() && std::filesystem::exists(f.json, ec);
  if (!f.json.empty()) WriteFileAtomically(f.json, json);
  if (k) {
    try {
      WriteFileAtomically(f.kalibr, k->text);
    } catch (const Error&) {
      if (!f.json.empty() && !json_existed) std::filesystem::remove(f.json, ec);
      throw;
    }
  }
  if (!f.json.empty()) fmt::print("wrote {}\n", f.json);
  if (!k) return;
  std::fflush(stdout);  // the warnings after the table, also when piped
  for (const auto& [name, v] :
       {std::pair{"accelerometer_random_walk", k->accel_random_walk},
        std::pair{"gyroscope_random_walk", k->gyro_random_walk},
        std::pair{"accelerometer_noise_density", k->accel_noise_density},
        std::pair{"gyroscope_noise_density", k->gyro_noise_density}}) {
    if (!v.upper_bound) continue;
    fmt::print(stderr,
               "{} {}: {} was not measured; the file has its upper bound "
               "{:.4g} (labelled in a comment){}\n",
               Paint(stderr, "mpcal: warning:", Tint::kLookAt),
               f.kalibr,
               name,
               k->Written(v),
               v.record_needed_s ? fmt::format("; record at least {} to measure it",
                                               FormatRecordLength(*v.record_needed_s))
                                 : "");
  }
  fmt::print("wrote {} (Kalibr IMU model: the largest axis of each sensor{})\n",
             f.kalibr,
             k->inflate == 1.0 ? std::string()
                               : fmt::format("; INFLATED x{:g}, as asked", k->inflate));
}

// The calibration of --calib, when given: the log's units default to its
// own. Without one, readings must be in physical units: counts have no
// scale.
std::optional<RecordingCorrector> MakeCorrector(NoiseFlags& f) {
  if (f.calib.empty()) {
    if (f.log.units == AccelUnits::kCounts) {
      throw Error(
          "noise needs the readings in physical units: give --units mps2 or g, or "
          "--calib with the sensor's calibration to turn its counts into m/s2");
    }
    if (f.log.gyro_in_counts) {
      throw Error(
          "noise needs the gyroscope in physical units: give --gyro-units rads or dps, "
          "or --calib with the IMU's calibration (mpcal.imu/1) to turn its counts "
          "into rad/s");
    }
    return std::nullopt;
  }
  const Calibration calibration = ReadCalibrationFile(f.calib);
  if (!f.units_given) f.log.units = calibration.input_units;
  if (calibration.gyroscope && !f.gyro_units_given) {
    f.log.gyro_in_counts = calibration.gyroscope->input_units == GyroUnits::kCounts;
    f.log.gyro_in_dps = calibration.gyroscope->input_units == GyroUnits::kDps;
  }
  // A gyroscope read in deg/s is in rad/s once read.
  return RecordingCorrector(
      calibration,
      f.log.units,
      f.log.gyro_in_counts ? GyroUnits::kCounts : GyroUnits::kRadps);
}

void Run(NoiseFlags& f) {
  ThrowIfInvalid(f.noise.Validate(), "noise");
  if (const std::string why = ValidateInflation(f.inflate); !why.empty())
    throw Error(ErrorKind::kOption, "--inflate: " + why);
  if (f.inflate != 1.0 && f.kalibr.empty())
    throw Error(ErrorKind::kOption,
                "--inflate multiplies the values of the Kalibr file; give --kalibr FILE "
                "with it");
  ThrowIfInvalid(f.detect.Validate(), "noise");
  if (!f.json.empty()) CheckOutput(f.json, {f.input, f.calib});
  if (!f.kalibr.empty()) CheckOutput(f.kalibr, {f.input, f.calib, f.json});
  const std::optional<RecordingCorrector> correct = MakeCorrector(f);

  const Analysis a = Analyse(f, correct ? &*correct : nullptr);
  const NoiseResult& r = a.result;
  for (const auto& w : a.warnings) fmt::print("  note: {}\n", w);
  fmt::print("{}: {}, {:.2f} h at {:.6g} Hz{}{}\n",
             f.input,
             Count(a.rows, "row"),
             a.span_s / 3600.0,
             r.rate_hz,
             a.has_gyro ? ", accelerometer and gyroscope" : ", accelerometer",
             f.calib.empty() ? "" : fmt::format(", corrected by {}", f.calib));
  fmt::print("analysed: {}: {}, {}\n",
             a.which,
             Count(r.samples, "sample"),
             FormatRecordLength(r.record_s));
  if (r.gaps > 0) {
    fmt::print(
        "  note: {} in time (samples lost); the samples are treated as evenly spaced\n",
        Count(r.gaps, "gap"));
  }
  const std::vector<AllanPoint>& c = r.accel_mps2.axes[0].curve;
  if (f.verbose) {
    fmt::print(
        "Allan deviation: overlapping, {} cluster times per axis from {:.3g} s to {:.4g} "
        "s "
        "(a quarter of the record), {} per octave; intervals {:.0f} %\n",
        c.size(),
        c.front().tau_s,
        c.back().tau_s,
        f.noise.allan.points_per_octave,
        100.0 * f.noise.allan.confidence);
  }
  PrintSensor(r.accel_mps2, false);
  if (r.gyro_radps) PrintSensor(*r.gyro_radps, true);
  fmt::print(
      "\nvalue [interval]; '< bound (not seen)' or '(model misses)': not measured, the "
      "largest value the "
      "record allows. Densities are continuous-time: per sample σ = N·√rate.\n");
  fmt::print("\n");
  PrintModelCheck(r.accel_mps2, false, f.noise.allan.confidence);
  if (r.gyro_radps) PrintModelCheck(*r.gyro_radps, true, f.noise.allan.confidence);
  PrintSensorVerdict(r.accel_mps2, false, r);
  if (r.gyro_radps) PrintSensorVerdict(*r.gyro_radps, true, r);
  if (f.verbose) {
    PrintFindings(r.accel_mps2, false, r);
    if (r.gyro_radps) PrintFindings(*r.gyro_radps, true, r);
  }

  WriteFiles(f, r);
}

// The log read, the files written and what goes into them.
void AddNoiseFileOptions(CLI::App* app, const std::shared_ptr<NoiseFlags>& f) {
  app->add_option("INPUT", f->input, "Log: CSV or text, '-' for standard input")
      ->required()
      ->check(InputPath);
  app->add_option("--json", f->json, "Write the curves and terms (mpcal.noise/1)")
      ->check(OutputPath);
  app->add_option("--kalibr",
                  f->kalibr,
                  "Write Kalibr's IMU noise file (imu.yaml) from the measured values")
      ->check(OutputPath);
  app->add_flag(
      "--strict",
      f->strict,
      "With --kalibr: a value not measured on any axis is an error (exit 1, no file "
      "written) instead of its upper bound");
  app->add_option(
         "--inflate",
         f->inflate,
         "With --kalibr: multiply the four noise values by this factor (at least 1; "
         "the file says so and gives the measured values beside them)")
      ->capture_default_str();
  app->add_option("--rostopic", f->rostopic, "The rostopic written in the Kalibr file")
      ->capture_default_str();
  app->add_option("--calib",
                  f->calib,
                  "Correct every row by this calibration first (mpcal.accelerometer/1, "
                  "or mpcal.imu/1 for the gyroscope too): a log of raw counts gives SI "
                  "figures. The log is read in the calibration's units unless --units "
                  "/ --gyro-units say otherwise")
      ->check(InputPath);
  app->add_flag(
      "--whole",
      f->whole,
      "Analyse every sample without detecting motion (default: the whole record "
      "when it is still throughout, else its longest still part)");
  app->add_flag("-v,--verbose",
                f->verbose,
                "Also print how the Allan deviation was made and, per term not measured, "
                "why and how long a record would show it");
}

// The Allan deviation's cluster times and intervals, and the terms of the
// model.
void AddNoiseModelOptions(CLI::App* app, const std::shared_ptr<NoiseFlags>& f) {
  app->add_option("--points-per-octave",
                  f->noise.allan.points_per_octave,
                  "Cluster times per factor of two")
      ->capture_default_str()
      ->check(NumberIn(1.0, 64.0))
      ->group("Allan deviation");
  app->add_option("--confidence",
                  f->noise.allan.confidence,
                  "Confidence level of the intervals (curve and terms)")
      ->capture_default_str()
      ->check(NumberIn(0.5, 0.999))
      ->group("Allan deviation");
  app->add_flag_callback(
         "--without-gauss-markov",
         [f] { f->noise.model_gauss_markov = false; },
         "Leave the Gauss-Markov process (a bump) out of the model: the model check "
         "then flags a bump instead of measuring it")
      ->group("Noise model");
  app->add_flag_callback(
         "--without-sinusoid",
         [f] { f->noise.model_sinusoid = false; },
         "Leave the sinusoid out of the model: the model check then flags one instead "
         "of measuring it")
      ->group("Noise model");
}

}  // namespace

// The command and its flags, in the order --help lists them.
void AddNoiseCommand(CLI::App& root) {
  auto f = std::make_shared<NoiseFlags>();
  CLI::App* app = root.add_subcommand(
      "noise",
      "Noise of a still IMU: overlapping Allan deviation with confidence intervals, the "
      "white noise, bias instability and random walk it shows (and how long to record "
      "for "
      "those it does not), JSON and Kalibr's imu.yaml");
  AddNoiseFileOptions(app, f);
  AddNoiseModelOptions(app, f);
  AddLogOptions(*app,
                f->log,
                {"raw ADC; needs --calib to scale them",
                 "raw ADC; needs --calib with an "
                 "IMU calibration to scale them"});
  AddGravityOptions(*app, f->gravity);
  AddDetectOptions(*app, f->detect);
  app->footer(
      "Examples:\n"
      "  mpcal simulate noise --hours 2 --rate 200 -o still.csv --truth truth.json\n"
      "  mpcal noise still.csv --json noise.json --kalibr imu.yaml\n"
      "  mpcal noise imu.csv --columns t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6 --units g\n"
      "  mpcal noise raw.csv --units counts --gyro-units counts --calib imu.json\n"
      "  mpcal report --noise noise.json -o report.html\n"
      "A line per sensor says good, look at (a term not measured: record longer) or "
      "do not use, coloured on a terminal; set NO_COLOR=1 for plain text.");
  app->callback([f, app] {
    f->units_given = app->count(std::string(FlagName(Option::kLogUnits))) > 0;
    f->gyro_units_given = app->count(std::string(FlagName(Option::kLogGyroUnits))) > 0;
    Run(*f);
  });
}

}  // namespace mpcal::cli
