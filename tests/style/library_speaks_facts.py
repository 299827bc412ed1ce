#!/usr/bin/env python3
"""The library returns facts; only apps/mpcal/ spells flags and subcommands.

Fails when a string literal in src/ or include/ names a flag the `mpcal`
command declares (taken from `mpcal SUBCOMMAND --help`, so a flag added
tomorrow is checked too) or a subcommand ("mpcal detect", "'detect'").
Comments may name them: they are for the engineers, not the users.

usage: library_speaks_facts.py MPCAL_BINARY PROJECT_ROOT
"""
import pathlib
import re
import subprocess
import sys

SUBCOMMANDS = ["calibrate", "detect", "apply", "repeat", "verify", "report",
               "simulate", "demo", "noise", "inspect"]
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')


def declared_flags(mpcal):
    flags = set()
    for command in [[]] + [[s] for s in SUBCOMMANDS] + [["simulate", "walk"],
                                                       ["simulate", "noise"],
                                                       ["simulate", "static"]]:
        out = subprocess.run([mpcal, *command, "--help"], capture_output=True,
                             text=True, check=False).stdout
        flags.update(FLAG.findall(out))
    flags -= {"--help", "--version"}
    return flags


def code_without_comments(text):
    # Drops // and /* */ comments but keeps string literals intact.
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            out.append("\n" * text.count("\n", i, n if j < 0 else j))
            i = n if j < 0 else j + 2
        elif text[i] == '"':
            m = STRING.match(text, i)
            end = m.end() if m else i + 1
            out.append(text[i:end])
            i = end
        elif text[i] == "'" and i + 2 < n:
            j = text.find("'", i + 1)
            j = i + 1 if j < 0 else j
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def main():
    mpcal, root = sys.argv[1], pathlib.Path(sys.argv[2])
    flags = declared_flags(mpcal)
    if len(flags) < 20:
        sys.exit(f"found only {len(flags)} flags in mpcal --help; is {mpcal} the command?")
    subcommand = re.compile(
        r"\bmpcal (?:%s)\b|'(?:%s)'" % ("|".join(SUBCOMMANDS), "|".join(SUBCOMMANDS)))
    problems = []
    files = sorted(root.glob("src/**/*.cc")) + sorted(root.glob("src/**/*.h")) + \
        sorted(root.glob("include/**/*.h"))
    for path in files:
        code = code_without_comments(path.read_text())
        for number, line in enumerate(code.splitlines(), 1):
            for literal in STRING.findall(line):
                # CSS custom properties (var(--ink)) are not flags.
                named = [f for f in FLAG.findall(literal)
                         if f in flags and f"var({f}" not in literal
                         and f"{f}:" not in literal]
                named += subcommand.findall(literal)
                if named:
                    problems.append(f"{path.relative_to(root)}:{number}: "
                                    f"{', '.join(named)} in {literal}")
    for problem in problems:
        print(problem)
    if problems:
        sys.exit(f"{len(problems)} string literals in the library name flags or "
                 "subcommands: return the Option or Stage (mpcal/advice.h) and let "
                 "apps/mpcal/explain*.cc spell it")
    print(f"checked {len(files)} files against {len(flags)} flags")


if __name__ == "__main__":
    main()
