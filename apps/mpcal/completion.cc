// The bash and zsh completion, written from the CLI11 tables: three lookup
// functions (the subcommands of a command, its flags, what a flag takes)
// generated from them, and for each shell one fixed function that walks the
// words typed so far.
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "reference.h"

namespace mpcal::cli {
namespace {

// A word in single quotes for the shell.
std::string Quote(const std::string& word) {
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string Words(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

std::vector<std::string> FlagNames(const CLI::Option& option) {
  std::vector<std::string> names;
  for (const std::string& s : option.get_snames()) names.push_back("-" + s);
  for (const std::string& l : option.get_lnames()) names.push_back("--" + l);
  return names;
}

// What completes the word after a flag: nothing for a flag without a value,
// its names for an enum, file names for other text, nothing for a number.
std::string Takes(const CLI::Option& option) {
  if (option.get_type_size() == 0) return "flag";
  if (const std::vector<std::string> choices = Choices(option); !choices.empty()) {
    return "choices " + Words(choices);
  }
  return option.get_type_name().starts_with("TEXT") ? "file" : "value";
}

struct Tables {
  std::string subcommands;
  std::string flags;
  std::string takes;
};

void AddCommand(const CLI::App& app, Tables& tables) {
  const std::string path = Words(CommandPath(app));
  std::vector<std::string> sub_names;
  for (const CLI::App* sub : Subcommands(app)) sub_names.push_back(sub->get_name());
  if (!sub_names.empty()) {
    tables.subcommands +=
        fmt::format("    {}) echo {} ;;\n", Quote(path), Quote(Words(sub_names)));
  }
  std::vector<std::string> flags;
  for (const CLI::Option* option : ListedOptions(app)) {
    if (option->get_positional()) continue;
    const std::vector<std::string> names = FlagNames(*option);
    flags.insert(flags.end(), names.begin(), names.end());
    const std::string takes = Takes(*option);
    if (takes == "flag") continue;
    std::string patterns;
    for (const std::string& name : names) {
      if (!patterns.empty()) patterns += '|';
      patterns += Quote(fmt::format("{} {}", path, name));
    }
    tables.takes += fmt::format("    {}) echo {} ;;\n", patterns, Quote(takes));
  }
  tables.flags += fmt::format("    {}) echo {} ;;\n", Quote(path), Quote(Words(flags)));
  for (const CLI::App* sub : Subcommands(app)) AddCommand(*sub, tables);
}

// The three lookups, in shell code both bash and zsh read.
std::string Lookups(const CLI::App& root) {
  Tables tables;
  AddCommand(root, tables);
  return fmt::format(
      "# The subcommands of a command ('' is mpcal itself).\n"
      "_mpcal_subcommands() {{\n  case $1 in\n{}  esac\n}}\n\n"
      "# The flags of a command.\n"
      "_mpcal_flags() {{\n  case $1 in\n{}  esac\n}}\n\n"
      "# What follows a command's flag: flag (nothing), choices NAME..., file or value.\n"
      "_mpcal_takes() {{\n  case \"$1 $2\" in\n{}    *) echo flag ;;\n  esac\n}}\n",
      tables.subcommands,
      tables.flags,
      tables.takes);
}

// The fixed part. The command is found from the subcommand words typed
// before the cursor, skipping each flag's value (the next word, or "=" and
// the word after it: bash splits --units=g at the "=").
constexpr const char* kBashCompleter = R"bash(
_mpcal() {
  local cur=${COMP_WORDS[COMP_CWORD]} command='' option='' takes word i=1
  while ((i < COMP_CWORD)); do
    word=${COMP_WORDS[i]}
    if [[ $word == -*=* ]]; then
      :
    elif [[ $word == -* ]]; then
      if [[ $(_mpcal_takes "$command" "$word") != flag ]]; then
        if [[ ${COMP_WORDS[i + 1]-} == = ]]; then ((i += 2)); else ((i += 1)); fi
      fi
    elif [[ " $(_mpcal_subcommands "$command") " == *" $word "* ]]; then
      command=${command:+$command }$word
    fi
    ((i += 1))
  done
  if [[ $cur == = ]]; then
    cur=''
    option=${COMP_WORDS[COMP_CWORD - 1]}
  elif ((COMP_CWORD > 2)) && [[ ${COMP_WORDS[COMP_CWORD - 1]} == = ]]; then
    option=${COMP_WORDS[COMP_CWORD - 2]}
  elif ((COMP_CWORD > 1)) && [[ ${COMP_WORDS[COMP_CWORD - 1]} == -* ]]; then
    option=${COMP_WORDS[COMP_CWORD - 1]}
  fi
  COMPREPLY=()
  if [[ -n $option ]]; then
    takes=$(_mpcal_takes "$command" "$option")
    case $takes in
      choices\ *)
        mapfile -t COMPREPLY < <(compgen -W "${takes#choices }" -- "$cur")
        return ;;
      file)
        compopt -o filenames 2>/dev/null
        mapfile -t COMPREPLY < <(compgen -f -- "$cur")
        return ;;
      value) return ;;
    esac
  fi
  if [[ $cur == -* ]]; then
    mapfile -t COMPREPLY < <(compgen -W "$(_mpcal_flags "$command")" -- "$cur")
  elif [[ -n $(_mpcal_subcommands "$command") ]]; then
    mapfile -t COMPREPLY < <(compgen -W "$(_mpcal_subcommands "$command")" -- "$cur")
  else
    compopt -o filenames 2>/dev/null
    mapfile -t COMPREPLY < <(compgen -f -- "$cur")
  fi
}
complete -F _mpcal mpcal
)bash";

// The same walk in zsh's terms: words and CURRENT, compadd and _files;
// zsh keeps --units=g one word, and compset moves past its "=".
constexpr const char* kZshCompleter = R"zsh(
local cur=$PREFIX command='' option='' takes word i=2
while (( i < CURRENT )); do
  word=${words[i]}
  if [[ $word == -*=* ]]; then
    :
  elif [[ $word == -* ]]; then
    if [[ $(_mpcal_takes "$command" "$word") != flag ]]; then (( i += 1 )); fi
  elif [[ " $(_mpcal_subcommands "$command") " == *" $word "* ]]; then
    command=${command:+$command }$word
  fi
  (( i += 1 ))
done
if [[ $cur == -*=* ]]; then
  option=${cur%%=*}
  compset -P '*='
elif (( CURRENT > 2 )) && [[ ${words[CURRENT - 1]} == -* ]]; then
  option=${words[CURRENT - 1]}
fi
if [[ -n $option ]]; then
  takes=$(_mpcal_takes "$command" "$option")
  case $takes in
    (choices\ *) compadd -- ${=takes#choices }; return ;;
    (file) _files; return ;;
    (value) return 1 ;;
  esac
fi
if [[ $cur == -* ]]; then
  compadd -- ${=$(_mpcal_flags "$command")}
elif [[ -n $(_mpcal_subcommands "$command") ]]; then
  compadd -- ${=$(_mpcal_subcommands "$command")}
else
  _files
fi
)zsh";

}  // namespace

std::string BashCompletion(const CLI::App& root) {
  return "# bash completion for mpcal, written by `mpcal --generate bash` from the "
         "flags\n"
         "# `mpcal --help` lists.\n\n" +
         Lookups(root) + kBashCompleter;
}

std::string ZshCompletion(const CLI::App& root) {
  return "#compdef mpcal\n"
         "# zsh completion for mpcal, written by `mpcal --generate zsh` from the flags\n"
         "# `mpcal --help` lists. zsh runs this file as the function _mpcal.\n\n" +
         Lookups(root) + kZshCompleter;
}

}  // namespace mpcal::cli
