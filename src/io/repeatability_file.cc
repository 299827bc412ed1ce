// The repeatability table as JSON ("mpcal.repeatability/1", written and read)
// and CSV (written).
#include "mpcal/repeatability_file.h"

#include <array>
#include <cmath>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.h"
#include "io/json_text.h"
#include "io/result_text.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

// Ordered: the keys come out in the order.
using json = JsonReader::json;

constexpr std::string_view kFormatFamily = "mpcal.repeatability";
// The JSON groups of the packed parameters: name, first packed index, and
// whether the group is a vector (x, y, z) or an object of scalar angles.
constexpr std::array<std::string_view, 3> kAngleKeys = {"yz", "zx", "zy"};

json ChangedJson(const ParameterRepeatability& p) {
  return p.changed ? json(*p.changed) : json(nullptr);
}

// One vector group (bias or scale) from packed parameters first..first+2.
json VectorGroup(const RepeatabilityResult& r, int first) {
  json values = json::array();
  for (int t = 0; t < r.trials; ++t) {
    json row = json::array();
    for (int a = 0; a < 3; ++a) row.push_back(r.parameters[first + a].values[t]);
    values.push_back(row);
  }
  json mean = json::array(), pop = json::array(), sample = json::array(),
       changed = json::array();
  for (int a = 0; a < 3; ++a) {
    const ParameterRepeatability& p = r.parameters[first + a];
    mean.push_back(p.mean);
    pop.push_back(p.std_population);
    sample.push_back(p.std_sample);
    changed.push_back(ChangedJson(p));
  }
  return json{{"values", values},
              {"mean", mean},
              {"std_population", pop},
              {"std_sample", sample},
              {"changed", changed}};
}

json ScalarGroup(const ParameterRepeatability& p) {
  return json{{"values", p.values},
              {"mean", p.mean},
              {"std_population", p.std_population},
              {"std_sample", p.std_sample},
              {"changed", ChangedJson(p)}};
}

// true, false, or null where the table has no verdict.
std::optional<bool> ReadChanged(const JsonReader& in,
                                const json& value,
                                const std::string& field) {
  if (value.is_null()) return std::nullopt;
  if (!value.is_boolean()) {
    in.Fail(fmt::format("field '{}' must be true, false or null, found {}",
                        field,
                        JsonReader::TypeName(value)));
  }
  return value.get<bool>();
}

// A value of the `index`th packed parameter (or, with `spread`, a standard
// deviation of its values), checked for what a calibration can hold
// (plausible.h): a bias of 1e308 would otherwise reach every table as inf.
void CheckPlausible(
    const JsonReader& in, double v, int index, const std::string& field, bool spread) {
  static constexpr std::array<std::string_view, 3> kKinds = {
      "accelerometer's bias", "scale-factor error", "non-orthogonality angle"};
  static constexpr std::array<std::string_view, 3> kUnits = {" m/s²", "", " rad"};
  const auto kind = static_cast<std::size_t>(index / 3);
  const double bound = MaxParameterMagnitude(index);
  // Values within ±bound spread by at most the width of that range.
  const bool plausible = spread ? v >= 0.0 && v <= 2.0 * bound : std::abs(v) <= bound;
  if (plausible) return;
  in.Fail(fmt::format("'{}' = {} is {} any {} ({}{:g}{})",
                      field,
                      v,
                      spread ? "not the spread of" : "beyond",
                      kKinds[kind],
                      spread ? "0 to " : "±",
                      spread ? 2.0 * bound : bound,
                      kUnits[kind]));
}

void ReadVectorGroup(const JsonReader& in,
                     const json& group,
                     const std::string& path,
                     int trials,
                     int first,
                     RepeatabilityResult& r) {
  const json& values = in.ArrayValue(in.Field(group, path, "values"),
                                     path + ".values",
                                     static_cast<std::size_t>(trials));
  for (int t = 0; t < trials; ++t) {
    const std::string row_path = fmt::format("{}.values[{}]", path, t);
    const json& row = in.ArrayValue(values[t], row_path, 3);
    for (int a = 0; a < 3; ++a) {
      const std::string item = fmt::format("{}[{}]", row_path, a);
      const double v = in.NumberValue(row[a], item);
      CheckPlausible(in, v, first + a, item, false);
      r.parameters[first + a].values.push_back(v);
    }
  }
  for (std::string_view key : {"mean", "std_population", "std_sample", "changed"}) {
    const std::string field_path = fmt::format("{}.{}", path, key);
    const json& arr = in.ArrayValue(in.Field(group, path, key), field_path, 3);
    for (int a = 0; a < 3; ++a) {
      ParameterRepeatability& p = r.parameters[first + a];
      const std::string item = fmt::format("{}[{}]", field_path, a);
      if (key == "changed") {
        p.changed = ReadChanged(in, arr[a], item);
        continue;
      }
      const double v = in.NumberValue(arr[a], item);
      CheckPlausible(in, v, first + a, item, key != "mean");
      (key == "mean"             ? p.mean
       : key == "std_population" ? p.std_population
                                 : p.std_sample) = v;
    }
  }
}

void ReadScalarGroup(const JsonReader& in,
                     const json& group,
                     const std::string& path,
                     int trials,
                     int index,
                     ParameterRepeatability& p) {
  const json& values = in.ArrayValue(in.Field(group, path, "values"),
                                     path + ".values",
                                     static_cast<std::size_t>(trials));
  for (int t = 0; t < trials; ++t) {
    const std::string item = fmt::format("{}.values[{}]", path, t);
    p.values.push_back(in.NumberValue(values[t], item));
    CheckPlausible(in, p.values.back(), index, item, false);
  }
  p.mean = in.Number(group, path, "mean");
  CheckPlausible(in, p.mean, index, path + ".mean", false);
  p.std_population = in.Number(group, path, "std_population");
  CheckPlausible(in, p.std_population, index, path + ".std_population", true);
  p.std_sample = in.Number(group, path, "std_sample");
  CheckPlausible(in, p.std_sample, index, path + ".std_sample", true);
  p.changed = ReadChanged(in, in.Field(group, path, "changed"), path + ".changed");
}

// CSV cells: shortest round-trip representation, empty when absent.
std::string Cell(const std::optional<double>& v) {
  return v ? fmt::format("{}", *v) : "";
}

}  // namespace

std::string RepeatabilityToJson(const RepeatabilityResult& result) {
  json angles = json::object();
  for (std::size_t k = 0; k < kAngleKeys.size(); ++k) {
    angles[std::string(kAngleKeys[k])] = ScalarGroup(result.parameters[6 + k]);
  }
  json out;
  out["format"] = kRepeatabilityFormat;
  out["trials"] = result.trials;
  json parameters;
  parameters["bias_mps2"] = VectorGroup(result, 0);
  parameters["scale_factor_error"] = VectorGroup(result, 3);
  parameters["non_orthogonality_rad"] = angles;
  out["parameters"] = parameters;
  return FiniteJsonText(out, 2, "the repeatability table");
}

RepeatabilityResult RepeatabilityFromJson(const std::string& text,
                                          const std::string& origin) {
  const JsonReader in(origin, Stage::kRepeat);
  const json doc = in.Parse(text);
  in.ExpectFormat(doc, kFormatFamily, 1);
  RepeatabilityResult r;
  r.trials = static_cast<int>(in.Integer(doc, "", "trials", 2, 1000000));
  for (int t = 0; t < r.trials; ++t)
    r.trial_names.push_back(fmt::format("trial {}", t + 1));
  const json& parameters = in.Object(doc, "", "parameters");
  ReadVectorGroup(in,
                  in.Field(parameters, "parameters", "bias_mps2"),
                  "parameters.bias_mps2",
                  r.trials,
                  0,
                  r);
  ReadVectorGroup(in,
                  in.Field(parameters, "parameters", "scale_factor_error"),
                  "parameters.scale_factor_error",
                  r.trials,
                  3,
                  r);
  const json& angles = in.Field(parameters, "parameters", "non_orthogonality_rad");
  for (std::size_t k = 0; k < kAngleKeys.size(); ++k) {
    const std::string path =
        fmt::format("parameters.non_orthogonality_rad.{}", kAngleKeys[k]);
    ReadScalarGroup(in,
                    in.Field(angles, "parameters.non_orthogonality_rad", kAngleKeys[k]),
                    path,
                    r.trials,
                    6 + static_cast<int>(k),
                    r.parameters[6 + k]);
  }
  return r;
}

RepeatabilityResult ReadRepeatabilityFile(const std::string& path) {
  return RepeatabilityFromJson(internal::ReadResultText(path, "a repeatability file"),
                               path);
}

std::string RepeatabilityToCsv(const RepeatabilityResult& result) {
  std::string out = "parameter";
  for (int t = 0; t < result.trials; ++t) out += fmt::format(",trial_{}", t + 1);
  out += ",mean,std_population,std_sample,changed,chi2,p_value\n";
  for (int p = 0; p < kNumModelParameters; ++p) {
    const ParameterRepeatability& row = result.parameters[static_cast<std::size_t>(p)];
    out += kParameterNames[static_cast<std::size_t>(p)];
    for (double v : row.values) out += fmt::format(",{}", v);
    out += fmt::format(",{},{},{},{},{},{}\n",
                       row.mean,
                       row.std_population,
                       row.std_sample,
                       row.changed ? (*row.changed ? "true" : "false") : "",
                       Cell(row.chi2),
                       Cell(row.p_value));
  }
  return out;
}

}  // namespace mpcal
