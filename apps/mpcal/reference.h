// The command's reference written from the CLI11 flag table that `--help`
// prints: a man page per command and the bash and zsh completion. The build runs
// `mpcal --generate` to write them, so neither can drift from the flags.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace mpcal::cli {

/// `mpcal --generate man DIR` writes every man page into the directory DIR
/// (which must exist); `mpcal --generate bash FILE` and `zsh FILE` write
/// the completion for that shell ("-": standard output). `args` are the words after
/// `--generate`. Returns the exit code. \throws CLI::ValidationError for other words (a
/// usage error),
///   mpcal::Error when a page cannot be written.
int Generate(const CLI::App& root, const std::vector<std::string>& args);

/// One roff page per command, for man(1) section 1: {"mpcal.1", text},
/// {"mpcal-calibrate.1", text}, {"mpcal-simulate-static.1", text}, ...
/// `version_line` goes into each page's header.
std::vector<std::pair<std::string, std::string>> ManualPages(
    const CLI::App& root, const std::string& version_line);

/// A bash script defining `_mpcal` and registering it for `mpcal`: the
/// subcommands, each command's flags, the choices of enum flags, file names
/// for the other text values.
std::string BashCompletion(const CLI::App& root);

/// The same for zsh: a `#compdef mpcal` file for a folder on $fpath, which
/// zsh runs as the function _mpcal.
std::string ZshCompletion(const CLI::App& root);

// Shared by both writers.

/// The subcommands of `app`, in the order --help lists them.
std::vector<const CLI::App*> Subcommands(const CLI::App& app);

/// The options --help lists: positionals, flags and options with a group.
std::vector<const CLI::Option*> ListedOptions(const CLI::App& app);

/// The names an enum option accepts, taken from its type ("TEXT:{mps2, g,
/// counts}", as OneOf describes them); empty for other options.
std::vector<std::string> Choices(const CLI::Option& option);

/// The command's words after "mpcal": {"simulate", "static"}; empty for the
/// root.
std::vector<std::string> CommandPath(const CLI::App& app);

}  // namespace mpcal::cli
