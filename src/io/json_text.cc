#include "io/json_text.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal {
namespace {

using json = nlohmann::ordered_json;

// The path of the first non-finite number under `node`, if any.
std::optional<std::string> FirstNonFinite(const json& node, const std::string& path) {
  if (node.is_number_float()) {
    if (std::isfinite(node.get<double>())) return std::nullopt;
    return path;
  }
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) {
      std::string child = path;
      if (!child.empty()) child += '.';
      child += key;
      if (auto p = FirstNonFinite(value, child)) return p;
    }
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (auto p = FirstNonFinite(node[i], fmt::format("{}[{}]", path, i))) return p;
    }
  }
  return std::nullopt;
}

}  // namespace

std::string FiniteJsonText(const json& doc, int indent, std::string_view what) {
  if (const std::optional<std::string> path = FirstNonFinite(doc, "")) {
    throw Error(fmt::format("cannot write {}: '{}' is not a finite number", what, *path));
  }
  return doc.dump(indent) + "\n";
}

}  // namespace mpcal
