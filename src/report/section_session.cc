#include <string>
#include <vector>

#include <fmt/format.h>

#include "report/html.h"
#include "report/line_plot.h"
#include "report/sections.h"

namespace mpcal::report {

namespace {

// Points per axis in the figure: a few thousand keep the page light while
// the min/max decimation keeps every turn visible.
constexpr std::size_t kMaxPointsPerAxis = 2400;

std::string UnitLabel(AccelUnits units) {
  switch (units) {
    case AccelUnits::kMps2:
      return "m/s\u00b2";
    case AccelUnits::kG:
      return "g";
    case AccelUnits::kCounts:
      return "counts";
  }
  return "";
}

// The calibration's positions are the intervals the fit used; shade those
// when they belong to this recording (most of them inside its time span).
bool PositionsBelongTo(const Calibration& c, double t0, double t1) {
  if (c.positions.empty()) return false;
  std::size_t inside = 0;
  for (const PositionSummary& p : c.positions) {
    if (p.start_s >= t0 - 1e-6 && p.end_s <= t1 + 1e-6) ++inside;
  }
  return 2 * inside > c.positions.size();
}

// The recording's figures: source, length, rate, units, what the detector
// found.
std::string SessionMeta(const ReportSession& session) {
  const Recording& r = session.recording;
  Table meta("meta");
  meta.Row({"Recording", r.source});
  meta.Row({"Samples", std::to_string(r.size())});
  if (r.size() >= 2) {
    const double duration = r.time_s.back() - r.time_s.front();
    meta.Row({"Duration",
              fmt::format(
                  "{:.1f} s, from {} s on the log's clock", duration, r.time_s.front())});
    if (duration > 0) {
      meta.Row({"Mean sample rate",
                Fixed(static_cast<double>(r.size() - 1) / duration, 1) + " Hz"});
    }
  }
  meta.Row({"Units of the readings", UnitLabel(r.units)});
  meta.Row(
      {"Static intervals detected", std::to_string(session.detection.intervals.size())});
  meta.Row({"Still stretches dropped as too short",
            std::to_string(session.detection.dropped_short)});
  meta.Row({"Motion threshold (moving std of the readings)",
            fmt::format("{} {} (quiet level {} {})",
                        Significant(session.detection.threshold, 3),
                        UnitLabel(r.units),
                        Significant(session.detection.quiet_level, 3),
                        UnitLabel(r.units))});
  return meta.Finish();
}

// The positions of the calibration (numbered as in its section) or, without
// one that belongs to this recording, the detected intervals, as bands.
void AddPositionBands(const ReportSession& session,
                      const Calibration* calibration,
                      bool use_calibration,
                      double t0,
                      LinePlotSpec& spec) {
  bool any_excluded = false;
  if (use_calibration) {
    for (std::size_t k = 0; k < calibration->positions.size(); ++k) {
      const PositionSummary& p = calibration->positions[k];
      spec.bands.push_back({p.start_s - t0,
                            p.end_s - t0,
                            std::to_string(k + 1),
                            p.used ? "band" : "band-excluded"});
      any_excluded |= !p.used;
    }
    spec.extra_legend.push_back(
        {"position of the calibration (numbered)", {}, true, "band", false});
    if (any_excluded) {
      spec.extra_legend.push_back(
          {"position excluded from the fit", {}, true, "band-excluded", false});
    }
  } else {
    for (std::size_t k = 0; k < session.detection.intervals.size(); ++k) {
      const StaticInterval& s = session.detection.intervals[k];
      spec.bands.push_back({s.start_s - t0, s.end_s - t0, std::to_string(k + 1), "band"});
    }
    spec.extra_legend.push_back(
        {"static interval detected (numbered)", {}, true, "band", false});
  }
}

}  // namespace

std::string SessionSection(const ReportSession& session, const Calibration* calibration) {
  const Recording& r = session.recording;
  std::string html = "<section id=\"session\">\n<h2>Session</h2>\n";
  html += SessionMeta(session);
  if (!r.warnings.empty()) html += WarningsList(r.warnings);
  if (r.empty()) return html + Paragraph("The recording is empty.") + "</section>\n";

  const double t0 = r.time_s.front();
  std::vector<double> t(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) t[i] = r.time_s[i] - t0;

  LinePlotSpec spec;
  spec.aria_label = "Accelerometer readings against time, static intervals shaded";
  spec.axes = {"time since the first sample (s)",
               fmt::format("reading ({})", UnitLabel(r.units))};
  spec.height = 340;
  static constexpr const char* kAxis[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    std::vector<double> v(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) v[i] = r.accel[i][a];
    Series s;
    s.name = fmt::format("{} axis", kAxis[a]);
    s.style = StandardStyle(a);
    s.style.width = 1.2;
    DecimateMinMax(t, v, kMaxPointsPerAxis, s.x, s.y);
    spec.series.push_back(std::move(s));
  }
  const bool use_calibration =
      calibration && PositionsBelongTo(*calibration, r.time_s.front(), r.time_s.back());
  AddPositionBands(session, calibration, use_calibration, t0, spec);
  html += Figure(
      LinePlot(spec),
      use_calibration
          ? "The three axes of the accelerometer as recorded; shaded: the static "
            "positions the calibration used, numbered as in the calibration section."
          : "The three axes of the accelerometer as recorded; shaded: the static "
            "intervals found by the detector with its default settings.");
  return html + "</section>\n";
}

}  // namespace mpcal::report
