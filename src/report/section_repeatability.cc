#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "report/display_units.h"
#include "report/dot_plot.h"
#include "report/html.h"
#include "report/sections.h"

namespace mpcal::report {

namespace {

using Row = ParameterRepeatability;

std::optional<double> MeanTrialStd(const Row& row) {
  if (row.trial_std.empty()) return std::nullopt;
  return std::accumulate(row.trial_std.begin(), row.trial_std.end(), 0.0) /
         static_cast<double>(row.trial_std.size());
}

// Decimals that give the row's finest uncertainty (spread or trial 1σ) two
// significant digits, so that all the values of a row line up.
int RowDecimals(const Row& row, double factor) {
  double unit = row.std_sample;
  if (const std::optional<double> s = MeanTrialStd(row); s && *s > 0) {
    unit = unit > 0 ? std::min(unit, *s) : *s;
  }
  unit *= factor;
  if (!(unit > 0) || !std::isfinite(unit)) return 4;
  return std::clamp(1 - static_cast<int>(std::floor(std::log10(unit))), 0, 9);
}

std::string TrialsTable(const RepeatabilityResult& rep, bool have_sigma) {
  std::vector<std::string> header = {"Parameter", "Unit"};
  for (int k = 0; k < rep.trials; ++k) header.push_back(fmt::format("trial {}", k + 1));
  header.insert(header.end(), {"mean", "std (n)", "std (n\u22121)"});
  if (have_sigma) header.push_back("mean 1\u03c3 of a trial");
  header.push_back("changed beyond 1\u03c3?");
  Table t("trials");
  t.Header(header);
  for (int i = 0; i < kNumModelParameters; ++i) {
    const Row& row = rep.parameters[static_cast<std::size_t>(i)];
    const DisplayUnit u = ParameterDisplayUnit(i);
    std::vector<std::string> cells = {std::string(ParameterShortLabel(i)),
                                      std::string(u.unit)};
    const int decimals = RowDecimals(row, u.factor);
    for (double v : row.values) cells.push_back(Fixed(v * u.factor, decimals));
    cells.push_back(Fixed(row.mean * u.factor, decimals));
    cells.push_back(Significant(row.std_population * u.factor, 3));
    cells.push_back(Significant(row.std_sample * u.factor, 3));
    if (have_sigma) {
      const std::optional<double> s = MeanTrialStd(row);
      cells.push_back(s ? Significant(*s * u.factor, 3) : "\u2014");
    }
    if (!row.changed) {
      cells.push_back(row.no_verdict_reason.empty() ? "\u2014" : row.no_verdict_reason);
    } else {
      cells.push_back(
          fmt::format("{}{}",
                      *row.changed ? "yes" : "no",
                      !row.p_value ? std::string()
                      : *row.p_value < 1e-15
                          ? std::string(" (p < 1e-15)")
                          : fmt::format(" (p = {})", Significant(*row.p_value, 2))));
    }
    t.Row(cells, row.changed.value_or(false) ? "bad" : "");
  }
  return t.Finish();
}

std::vector<std::string> TrialNames(const RepeatabilityResult& rep) {
  std::vector<std::string> names;
  names.reserve(static_cast<std::size_t>(std::max(rep.trials, 0)));
  for (int k = 0; k < rep.trials; ++k) names.push_back(fmt::format("trial {}", k + 1));
  return names;
}

// Deviation of every trial from the mean in units of the trials' own mean
// 1σ: the ±1 band is what the uncertainty explains.
std::string NormalisedSpreadPlot(const RepeatabilityResult& rep) {
  DotPlotSpec spec;
  spec.aria_label = "Deviation of each trial from the mean, in units of 1 sigma";
  spec.x_label =
      "deviation from the mean across trials (in units of the trials' 1\u03c3)";
  spec.groups = TrialNames(rep);
  spec.band_legend = "\u00b11\u03c3";
  spec.x_include = Interval{-3.0, 3.0};
  // The bias moves by hundreds of σ between power-ups: past ±10σ the points
  // sit at the edge with their value, so that ±1σ stays readable.
  spec.clip_abs = 10.0;
  for (int i = 0; i < kNumModelParameters; ++i) {
    const Row& row = rep.parameters[static_cast<std::size_t>(i)];
    const std::optional<double> s = MeanTrialStd(row);
    DotRow dots{std::string(ParameterShortLabel(i)), {}, Interval{-1.0, 1.0}};
    for (double v : row.values) {
      dots.values.push_back(s && *s > 0 ? (v - row.mean) / *s : std::nan(""));
    }
    spec.rows.push_back(dots);
  }
  return Figure(DotPlot(spec),
                "Each trial's value minus the mean over the trials, divided by the mean "
                "1\u03c3 of the trials. Points outside the shaded band moved between "
                "sessions by more than the calibration's own uncertainty (expected for "
                "the bias, which changes at every power-up).");
}

// Without per-trial 1σ the rows cannot share an axis: one plot per unit.
std::string SpreadPlotsInUnits(const RepeatabilityResult& rep) {
  std::string html;
  static constexpr struct {
    int first;
    const char* what;
  } kGroups[] = {{0, "bias"}, {3, "scale-factor error"}, {6, "non-orthogonality"}};
  for (const auto& g : kGroups) {
    const DisplayUnit u = ParameterDisplayUnit(g.first);
    DotPlotSpec spec;
    spec.aria_label = fmt::format("Deviation of each trial from the mean, {}", g.what);
    spec.x_label = fmt::format("deviation from the mean across trials ({})", u.unit);
    spec.groups = TrialNames(rep);
    for (int i = g.first; i < g.first + 3; ++i) {
      const Row& row = rep.parameters[static_cast<std::size_t>(i)];
      DotRow dots{std::string(ParameterShortLabel(i)), {}, std::nullopt};
      for (double v : row.values) dots.values.push_back((v - row.mean) * u.factor);
      spec.rows.push_back(dots);
    }
    html += Figure(
        DotPlot(spec),
        fmt::format(
            "Each trial's {} minus the mean over the trials, in {}.", g.what, u.unit));
  }
  return html;
}

}  // namespace

std::string RepeatabilitySection(const RepeatabilityResult& rep) {
  bool have_sigma = false;
  for (const Row& row : rep.parameters) have_sigma |= !row.trial_std.empty();
  std::string html = "<section id=\"repeatability\">\n<h2>Repeatability</h2>\n";
  html += Paragraph(fmt::format(
      "{} calibrations of one device. Bias in mg, scale-factor error in ppm, "
      "non-orthogonality in mrad. std (n) divides by the number of trials (the "
      "paper's \u201cdesvio padr\u00e3o\u201d), std (n\u22121) by one less.",
      rep.trials));
  // Names other than the default "trial k" are the input files: list them.
  bool named = false;
  for (std::size_t k = 0; k < rep.trial_names.size(); ++k) {
    named |= rep.trial_names[k] != fmt::format("trial {}", k + 1);
  }
  if (named) {
    Table names("meta");
    for (std::size_t k = 0; k < rep.trial_names.size(); ++k) {
      names.Row({fmt::format("trial {}", k + 1), rep.trial_names[k]});
    }
    html += names.Finish();
  }
  html += TrialsTable(rep, have_sigma);
  std::vector<std::string> changed;
  std::vector<std::string> stable;
  for (int i = 0; i < kNumModelParameters; ++i) {
    const std::optional<bool>& c = rep.parameters[static_cast<std::size_t>(i)].changed;
    if (c) (*c ? changed : stable).push_back(std::string(ParameterShortLabel(i)));
  }
  if (!changed.empty() || !stable.empty()) {
    html += Paragraph(fmt::format(
        "Changed between sessions beyond their uncertainty: {}. Within it: {}.",
        changed.empty() ? std::string("none")
                        : fmt::format("{}", fmt::join(changed, ", ")),
        stable.empty() ? std::string("none")
                       : fmt::format("{}", fmt::join(stable, ", "))));
  }
  if (!rep.notes.empty()) html += WarningsList(rep.notes);
  html += have_sigma ? NormalisedSpreadPlot(rep) : SpreadPlotsInUnits(rep);
  return html + "</section>\n";
}

}  // namespace mpcal::report
