#include <cmath>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "mpcal/coverage.h"

namespace mpcal {
namespace {

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// JSON has no NaN: a missing value is null.
nlohmann::json Num(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

nlohmann::json IntervalsJson(const DetectResult& detection,
                             const CoverageResult& coverage) {
  using nlohmann::json;
  json intervals = json::array();
  for (std::size_t k = 0; k < detection.intervals.size(); ++k) {
    const StaticInterval& iv = detection.intervals[k];
    json j = {{"begin", iv.begin},
              {"end", iv.end},
              {"samples", iv.samples()},
              {"start_s", iv.start_s},
              {"end_s", iv.end_s},
              {"duration_s", iv.duration_s()},
              {"mean", Vec(iv.mean)},
              {"std", Vec(iv.std)},
              {"noise", iv.noise()}};
    if (k < coverage.directions.size()) {
      j["direction"] = Vec(coverage.directions[k]);
      j["angle_to_previous_deg"] = Num(coverage.angle_to_previous_deg[k]);
    }
    intervals.push_back(j);
  }
  return intervals;
}

nlohmann::json TurnsJson(std::span<const Turn> turns) {
  using nlohmann::json;
  json turn_list = json::array();
  for (const Turn& t : turns) {
    turn_list.push_back({{"from", t.from + 1},
                         {"to", t.from + 2},
                         {"start_s", t.start_s},
                         {"end_s", t.end_s},
                         {"duration_s", t.duration_s()},
                         {"angle_deg", t.angle_deg},
                         {"axis", Vec(t.axis)},
                         {"tilt_deg", t.tilt_deg}});
  }
  return turn_list;
}

}  // namespace

std::string DetectionReportJson(const DetectResult& detection,
                                const CoverageResult& coverage,
                                const CoverageOptions& options,
                                const std::string& source,
                                const DetectionWords* words,
                                std::span<const Turn> turns) {
  using nlohmann::json;
  DetectionWords plain;
  if (words == nullptr) {
    plain.message = Describe(detection.finding);
    for (const auto& n : detection.notes) plain.notes.push_back(Describe(n));
    for (const auto& p : coverage.problems) plain.problems.push_back(Describe(p));
    for (const auto& a : coverage.advice) plain.advice.push_back(Describe(a));
    plain.summary = Summary(coverage);
    words = &plain;
  }
  const json intervals = IntervalsJson(detection, coverage);
  auto names = [](const std::vector<int>& idx) {
    json out = json::array();
    for (int i : idx)
      out.push_back(CanonicalDirections()[static_cast<std::size_t>(i)].down);
    return out;
  };
  json axes = json::object();
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = coverage.axes[static_cast<std::size_t>(i)];
    axes[std::string(1, static_cast<char>('x' + i))] = {
        {"near_up", ax.near_up},
        {"near_down", ax.near_down},
        {"closest_up_deg", ax.closest_up_deg},
        {"closest_down_deg", ax.closest_down_deg},
        {"largest_gap_deg", ax.largest_gap_deg}};
  }
  json doc = {{"format", "mpcal.detection/1"},
              {"source", source},
              {"units", std::string(ToString(options.units))},
              {"detection",
               {{"window_samples", detection.window_samples},
                {"sample_period_s", detection.sample_period_s},
                {"quiet_level", detection.quiet_level},
                {"threshold", detection.threshold},
                {"threshold_capped", detection.threshold_capped},
                {"gravity_units", detection.gravity_units},
                {"dropped_short", detection.dropped_short},
                {"merged", detection.merged},
                {"clipped_samples", detection.clipped_samples},
                {"dropped_clipped", detection.dropped_clipped},
                {"warnings", words->notes},
                {"longest_still_s", detection.longest_still_s},
                {"still_fraction", detection.still_fraction},
                {"message", words->message}}},
              {"intervals", intervals},
              {"coverage",
               {{"model", std::string(ToString(options.model))},
                {"verdict", std::string(ToString(coverage.verdict))},
                {"good_enough", coverage.good_enough()},
                {"positions", coverage.positions},
                {"distinct_positions", coverage.distinct_positions},
                {"required_positions", coverage.required_positions},
                {"recommended_positions", coverage.recommended_positions},
                {"offset", Vec(coverage.normalisation.centre)},
                {"radius", coverage.normalisation.radius},
                {"offset_fitted", coverage.normalisation.fitted},
                {"near_deg", options.near_deg},
                {"covered", names(coverage.covered)},
                {"missing", names(coverage.missing)},
                {"axes", axes},
                {"largest_empty_cap_deg", coverage.largest_empty_cap_deg},
                {"emptiest_direction", Vec(coverage.emptiest_direction)},
                {"observability", coverage.observability},
                {"problems", words->problems},
                {"advice", words->advice},
                {"summary", words->summary}}}};
  if (!turns.empty()) doc["turns"] = TurnsJson(turns);
  return doc.dump(2) + "\n";
}

}  // namespace mpcal
