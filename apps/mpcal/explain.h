// The one place where the library's facts become the words and flag names a
// command-line user reads: an Option is spelled as the flag that sets it (the
// same table declares the flags, in cli_options.cc), a Stage as the
// subcommand that runs it. Each room's findings have their explainer beside
// this one (explain_<room>.cc), built on these.
#pragma once

#include <string>
#include <string_view>

#include "mpcal/advice.h"
#include "mpcal/error.h"

namespace mpcal::cli {

/// The flag that sets `option` ("--units"), as declared.
std::string_view FlagName(Option option);
/// The placeholder for a value the user chooses ("HZ" for --rate).
std::string_view FlagPlaceholder(Option option);
/// "--units g", or "--rate HZ" when the value is the user's to choose.
std::string FlagWithValue(const Setting& setting);
/// The subcommand that runs `stage` ("detect").
std::string_view SubcommandName(Stage stage);

/// The advice as an instruction: "give --units g or --units counts", "run
/// 'mpcal detect a.csv --units counts'"; empty for empty advice.
std::string ExplainAdvice(const Advice& advice);

/// The error as the user reads it: the library's sentence, then the advice.
std::string Explain(const Error& error);

}  // namespace mpcal::cli
