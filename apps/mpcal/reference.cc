// `mpcal --generate` and what the man pages and the completion share: which
// commands and options the help lists, and the choices of an enum option.
#include "reference.h"

#include <string>
#include <vector>

#include "mpcal/atomic_file.h"

namespace mpcal::cli {

std::vector<const CLI::App*> Subcommands(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App* sub) {
    return !sub->get_name().empty() && !sub->get_disabled() && !sub->get_group().empty();
  });
}

std::vector<const CLI::Option*> ListedOptions(const CLI::App& app) {
  return app.get_options(
      [](const CLI::Option* option) { return !option->get_group().empty(); });
}

std::vector<std::string> Choices(const CLI::Option& option) {
  const std::string type = option.get_type_name();
  const std::size_t open = type.find('{');
  const std::size_t close = type.find('}', open);
  std::vector<std::string> choices;
  if (open == std::string::npos || close == std::string::npos) return choices;
  for (std::string& choice :
       CLI::detail::split(type.substr(open + 1, close - open - 1), ',')) {
    choice = CLI::detail::trim_copy(choice);
    if (!choice.empty()) choices.push_back(choice);
  }
  return choices;
}

std::vector<std::string> CommandPath(const CLI::App& app) {
  std::vector<std::string> words;
  for (const CLI::App* a = &app; a->get_parent() != nullptr; a = a->get_parent()) {
    words.insert(words.begin(), a->get_name());
  }
  return words;
}

int Generate(const CLI::App& root, const std::vector<std::string>& args) {
  if (args.size() == 2 && args[0] == "man") {
    for (const auto& [name, text] :
         ManualPages(root, std::string("mpcal ") + MPCAL_VERSION)) {
      WriteFileAtomically(args[1] + "/" + name, text);
    }
    return 0;
  }
  if (args.size() == 2 && (args[0] == "bash" || args[0] == "zsh")) {
    WriteFileAtomically(args[1],
                        args[0] == "bash" ? BashCompletion(root) : ZshCompletion(root));
    return 0;
  }
  throw CLI::ValidationError("--generate",
                             "give 'man DIRECTORY' (the man pages), 'bash FILE' or 'zsh "
                             "FILE' (the completion; '-' for standard output)");
}

}  // namespace mpcal::cli
