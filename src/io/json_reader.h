// Reading mpcal's own JSON files (the calibration, the repeatability table,
// the verification result, the noise analysis) with errors that name the file
// and the field, in one vocabulary for all of them:
// `calibration file 'c.json': field 'fit.iterations' must be an integer, found a
// string`.
//
// Private to the io room: nlohmann stays out of the public headers, and every
// file format is read and written in src/io/<format>_file.cc.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "mpcal/advice.h"

namespace mpcal {

/// Walks a parsed document; every accessor takes the path of the object it
/// reads from ("" for the top level) so that a message names the field
/// ("fit.iterations", "positions[3].mean_mps2[1]").
/// Every failure throws mpcal::Error: ErrorKind::kFormat when the document is
/// not of the format expected (advice: the stage that writes it), kInput for a
/// malformed document or field.
class JsonReader {
 public:
  using json = nlohmann::ordered_json;

  /// `origin` starts every message ("calibration file 'c.json'", or a path);
  /// `producer` is the stage that writes such files (Stage::kCalibrate), the
  /// advice where a file is not what was expected.
  JsonReader(std::string origin, Stage producer);

  /// Parses `text`; an empty text or invalid JSON is an error.
  json Parse(std::string_view text) const;

  /// Checks that `doc` is an object whose "format" is `family`/`major`
  /// (a minor version, "/1.2", is accepted: it only adds fields).
  void ExpectFormat(const json& doc, std::string_view family, int major) const;

  /// Throws Error(ErrorKind::kInput, "`origin`: `message`").
  [[noreturn]] void Fail(const std::string& message) const;
  /// Throws Error(ErrorKind::kFormat, "`origin`: `message`"), advising the
  /// stage that writes the file expected.
  [[noreturn]] void FailFormat(const std::string& message) const;

  /// "a number", "a string", "true/false", "null", "an array", "an object".
  static std::string TypeName(const json& value);
  /// `path`.`key`, or `key` at the top level.
  static std::string Join(const std::string& path, std::string_view key);

  /// The field `key` of `object`; missing is an error.
  const json& Field(const json& object,
                    const std::string& path,
                    std::string_view key) const;
  const json& Object(const json& object,
                     const std::string& path,
                     std::string_view key) const;
  double Number(const json& object, const std::string& path, std::string_view key) const;
  /// Absent: nullopt; present, it must be a finite number.
  std::optional<double> OptionalNumber(const json& object,
                                       const std::string& path,
                                       std::string_view key) const;
  /// An integer in [min, max]; `max` defaults to what an int holds, so that
  /// a larger value cannot wrap around to a negative one.
  long long Integer(const json& object,
                    const std::string& path,
                    std::string_view key,
                    long long min,
                    long long max = std::numeric_limits<int>::max()) const;
  bool Bool(const json& object, const std::string& path, std::string_view key) const;
  std::string String(const json& object,
                     const std::string& path,
                     std::string_view key) const;
  /// An array of 3 finite numbers (x, y, z).
  Eigen::Vector3d Vector(const json& object,
                         const std::string& path,
                         std::string_view key) const;

  /// `value` itself, named `field` in messages: a finite number (JSON has no
  /// NaN or infinity; writers put null in their place).
  double NumberValue(const json& value, const std::string& field) const;
  /// `value` itself: an array of exactly `size` entries.
  const json& ArrayValue(const json& value,
                         const std::string& field,
                         std::size_t size) const;

 private:
  std::string origin_;
  Stage producer_;
};

}  // namespace mpcal
