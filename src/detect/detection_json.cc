#include <cmath>
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

}  // namespace

std::string DetectionReportJson(const DetectResult& detection,
                                const CoverageResult& coverage,
                                const CoverageOptions& options,
                                const std::string& source) {
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
  const json doc = {{"format", "mpcal.detection/1"},
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
                      {"warnings", detection.warnings},
                      {"longest_still_s", detection.longest_still_s},
                      {"still_fraction", detection.still_fraction},
                      {"message", detection.message}}},
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
                      {"problems", coverage.problems},
                      {"advice", coverage.advice},
                      {"summary", coverage.summary}}}};
  return doc.dump(2) + "\n";
}

}  // namespace mpcal
