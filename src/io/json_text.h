// Writing mpcal's own JSON files: the document as text, refused when a number
// in it is not finite. nlohmann writes NaN and infinity as `null`, which a
// reader would take for "absent" and a schema may accept: a wrong number
// passed on without a word. The writers of the calibration and the IMU file
// check each field as they fill it; the others go through here.
//
// Private to the io room, as json_reader.h.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace mpcal {

/// `doc` as text with `indent`, ending in a newline.
/// \throws mpcal::Error naming `what` ("the repeatability table") and the
///   first non-finite number's path ("trials[2].bias_mps2[0]").
std::string FiniteJsonText(const nlohmann::ordered_json& doc,
                           int indent,
                           std::string_view what);

}  // namespace mpcal
