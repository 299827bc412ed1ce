#include "io/json_reader.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal {

JsonReader::JsonReader(std::string origin, Stage producer)
    : origin_(std::move(origin)), producer_(producer) {}

void JsonReader::Fail(const std::string& message) const {
  throw Error(ErrorKind::kInput, fmt::format("{}: {}", origin_, message));
}

void JsonReader::FailFormat(const std::string& message) const {
  Advice advice;
  advice.stage = producer_;
  throw Error(
      ErrorKind::kFormat, fmt::format("{}: {}", origin_, message), std::move(advice));
}

JsonReader::json JsonReader::Parse(std::string_view text) const {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    FailFormat("the file is empty");
  }
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    // parse_error for bad syntax, out_of_range for a number beyond a double.
    // nlohmann's messages start with "[json.exception.parse_error.101] ".
    std::string what = e.what();
    const auto bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    Fail(fmt::format("not valid JSON: {}", what));
  }
}

void JsonReader::ExpectFormat(const json& doc, std::string_view family, int major) const {
  const std::string expected = fmt::format("{}/{}", family, major);
  if (!doc.is_object()) {
    FailFormat(fmt::format("expected a JSON object with \"format\": \"{}\", found {}",
                           expected,
                           TypeName(doc)));
  }
  if (!doc.contains("format")) {
    FailFormat(fmt::format("no 'format' field (expected \"format\": \"{}\")", expected));
  }
  const std::string format = String(doc, "", "format");
  const std::string prefix = fmt::format("{}/", family);
  const std::string version =
      format.rfind(prefix, 0) == 0 ? format.substr(prefix.size()) : "";
  const std::string version_major = version.substr(0, version.find('.'));
  if (version_major.empty() || version_major.size() > 5 ||
      version_major.find_first_not_of("0123456789") != std::string::npos) {
    FailFormat(fmt::format("format '{}' is not '{}'", format, expected));
  }
  if (std::stoi(version_major) != major) {
    // Another version of the right file: no stage to run would fix it.
    throw Error(
        ErrorKind::kFormat,
        fmt::format(
            "{}: format '{}' is version {} of the format; this mpcal reads version "
            "{} ('{}'): use the "
            "mpcal that wrote it, or a newer mpcal",
            origin_,
            format,
            version_major,
            major,
            expected));
  }
}

std::string JsonReader::TypeName(const json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "true/false";
  if (value.is_null()) return "null";
  if (value.is_array()) return "an array";
  return "an object";
}

std::string JsonReader::Join(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

const JsonReader::json& JsonReader::Field(const json& object,
                                          const std::string& path,
                                          std::string_view key) const {
  if (!object.is_object()) {
    Fail(fmt::format("'{}' must be an object, found {}",
                     path.empty() ? "(top)" : path,
                     TypeName(object)));
  }
  const auto it = object.find(key);
  if (it == object.end()) Fail(fmt::format("missing field '{}'", Join(path, key)));
  return *it;
}

const JsonReader::json& JsonReader::Object(const json& object,
                                           const std::string& path,
                                           std::string_view key) const {
  const json& j = Field(object, path, key);
  if (!j.is_object()) {
    Fail(fmt::format(
        "field '{}' must be an object, found {}", Join(path, key), TypeName(j)));
  }
  return j;
}

double JsonReader::NumberValue(const json& value, const std::string& field) const {
  if (value.is_null())
    Fail(fmt::format("field '{}' is null (a non-finite value?)", field));
  if (!value.is_number()) {
    Fail(fmt::format("field '{}' must be a number, found {}", field, TypeName(value)));
  }
  const double v = value.get<double>();
  if (!std::isfinite(v)) Fail(fmt::format("field '{}' is not finite", field));
  return v;
}

double JsonReader::Number(const json& object,
                          const std::string& path,
                          std::string_view key) const {
  return NumberValue(Field(object, path, key), Join(path, key));
}

std::optional<double> JsonReader::OptionalNumber(const json& object,
                                                 const std::string& path,
                                                 std::string_view key) const {
  if (!object.contains(key)) return std::nullopt;
  return Number(object, path, key);
}

long long JsonReader::Integer(const json& object,
                              const std::string& path,
                              std::string_view key,
                              long long min,
                              long long max) const {
  const json& j = Field(object, path, key);
  const std::string field = Join(path, key);
  if (!j.is_number_integer()) {
    Fail(fmt::format("field '{}' must be an integer, found {}",
                     field,
                     j.is_number() ? "a fractional number" : TypeName(j)));
  }
  if (j.is_number_unsigned() &&
      j.get<unsigned long long>() > static_cast<unsigned long long>(max)) {
    Fail(fmt::format("field '{}' must be at most {}, found {}",
                     field,
                     max,
                     j.get<unsigned long long>()));
  }
  const long long v = j.get<long long>();
  if (v < min)
    Fail(fmt::format("field '{}' must be at least {}, found {}", field, min, v));
  if (v > max)
    Fail(fmt::format("field '{}' must be at most {}, found {}", field, max, v));
  return v;
}

bool JsonReader::Bool(const json& object,
                      const std::string& path,
                      std::string_view key) const {
  const json& j = Field(object, path, key);
  if (!j.is_boolean()) {
    Fail(fmt::format(
        "field '{}' must be true or false, found {}", Join(path, key), TypeName(j)));
  }
  return j.get<bool>();
}

std::string JsonReader::String(const json& object,
                               const std::string& path,
                               std::string_view key) const {
  const json& j = Field(object, path, key);
  if (!j.is_string()) {
    Fail(fmt::format(
        "field '{}' must be a string, found {}", Join(path, key), TypeName(j)));
  }
  return j.get<std::string>();
}

const JsonReader::json& JsonReader::ArrayValue(const json& value,
                                               const std::string& field,
                                               std::size_t size) const {
  if (!value.is_array() || value.size() != size) {
    Fail(fmt::format(
        "field '{}' must be an array of {} entries, found {}",
        field,
        size,
        value.is_array() ? fmt::format("{}", value.size()) : TypeName(value)));
  }
  return value;
}

Eigen::Vector3d JsonReader::Vector(const json& object,
                                   const std::string& path,
                                   std::string_view key) const {
  const std::string field = Join(path, key);
  const json& j = Field(object, path, key);
  if (!j.is_array() || j.size() != 3) {
    Fail(fmt::format("field '{}' must be an array of 3 numbers (x, y, z), found {}",
                     field,
                     j.is_array() ? fmt::format("{} elements", j.size()) : TypeName(j)));
  }
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = NumberValue(j[i], fmt::format("{}[{}]", field, i));
  return v;
}

}  // namespace mpcal
