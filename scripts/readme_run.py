#!/usr/bin/env python3
"""Runs the commands shown in README.md and docs/ and compares (or replaces)
their output.

The README and the pages under docs/ show commands as `$ command` lines
inside fenced blocks, each followed by what it printed. This script runs every block in a scratch
directory of its own (with the repository's `tests/`, `bench/` and the build's
`mpcal` reachable, so the paths a clone has work), feeding each command to
bash with stderr merged into stdout, and then either checks that each page
shows what the commands print today (`--check`, run by CI) or writes the new
output into the page (`--update`).

  - A line `...` in the README's output stands for any number of lines (used
    to shorten long outputs); --update keeps the same number of lines before
    and after it.
  - A block is skipped when the line before its opening fence is a skip mark
    (timings, benches that take minutes, inputs a clone does not have). A
    skipped block can go stale silently, so its mark says what made it and
    when:

        <!-- readme-run: skip; made 2026-11-25 by bash bench/noise_bench.sh build 3 8 400 -->

    `--check` (and `--marks`, which checks only the marks and needs no
    build) fails on a mark without a valid date (not after today) and a
    command, or not followed by a fence; `--update` names such marks.
  - A block whose opening fence follows `<!-- readme-run: continue -->` runs
    in the scratch directory of the block run before it, with the files its
    commands wrote (an output shown in two parts of the README).

  scripts/readme_run.py --check  [--build build] [--readme PAGE ...]
  scripts/readme_run.py --update [--build build] [--readme PAGE ...]
  scripts/readme_run.py --marks  [--readme PAGE ...]

Without --readme, every page: README.md and docs/**/*.md.
"""
import argparse
import datetime
import os
import re
import subprocess
import sys
import tempfile

# Any line that means to be a mark: a skip mark or CONTINUE_MARK.
MARK_START = re.compile(r"^\s*<!--\s*readme-run\b")
CONTINUE_MARK = "<!-- readme-run: continue -->"
SKIP_START = re.compile(r"^\s*<!--\s*readme-run:\s*skip\b")
SKIP_MARK = re.compile(
    r"^<!-- readme-run: skip; made (?P<date>\d{4}-\d{2}-\d{2}) by (?P<command>\S.*?) -->$")
SKIP_FORM = "<!-- readme-run: skip; made YYYY-MM-DD by COMMAND -->"
ELLIPSIS = "..."


def is_skip_mark(line):
    """Whether `line` marks the next block as skipped (well formed or not: a
    malformed mark still keeps its block from running, and check_marks
    reports it)."""
    return SKIP_START.match(line) is not None


def check_marks(lines, today=None):
    """[(line number, problem)] of the marks in `lines`: each is a skip mark
    naming the date (YYYY-MM-DD, not after `today`) and the command that made
    its block, or CONTINUE_MARK, on the line before a block's opening
    fence."""
    today = today or datetime.date.today()
    problems = []
    for i, line in enumerate(lines):
        if not MARK_START.match(line):
            continue
        if line.strip() == CONTINUE_MARK:
            if i + 1 >= len(lines) or not lines[i + 1].startswith("```"):
                problems.append((i + 1, "a mark must be the line right before a block's "
                                        "opening fence"))
            continue
        m = SKIP_MARK.match(line.strip())
        if not m:
            problems.append((i + 1, f"a skip mark must read {SKIP_FORM}: the date and "
                                    "the command that made the block, so that a stale "
                                    "block can be found and made again"))
            continue
        try:
            made = datetime.date.fromisoformat(m.group("date"))
        except ValueError:
            problems.append((i + 1, f"'{m.group('date')}' is not a date (YYYY-MM-DD)"))
            continue
        if made > today:
            problems.append((i + 1, f"the date {made} is after today ({today})"))
        if i + 1 >= len(lines) or not lines[i + 1].startswith("```"):
            problems.append((i + 1, "a mark must be the line right before a block's "
                                    "opening fence"))
    return problems


def parse_blocks(lines):
    """Yields (start, end, skip, cont) of fenced blocks holding `$ ` lines: their
    line range, whether they are skipped, whether they continue the block run
    before them."""
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            body = lines[i + 1:j]
            if any(l.startswith("$ ") for l in body):
                skip = i > 0 and is_skip_mark(lines[i - 1])
                cont = i > 0 and lines[i - 1].strip() == CONTINUE_MARK
                yield i + 1, j, skip, cont
            i = j + 1
        else:
            i += 1


def split_commands(body):
    """[(command, [expected lines])] from a block's lines."""
    steps = []
    for line in body:
        if line.startswith("$ "):
            steps.append((line[2:], []))
        elif steps:
            steps[-1][1].append(line)
    return steps


def scratch_directory(root, build):
    """A new scratch directory with the repository's `tests/`, `bench/`,
    `examples/` and the build reachable (a TemporaryDirectory)."""
    scratch = tempfile.TemporaryDirectory(prefix="mpcal_readme_")
    for name in ("tests", "bench", "examples"):
        os.symlink(os.path.join(root, name), os.path.join(scratch.name, name))
    os.symlink(build, os.path.join(scratch.name, "build"))
    return scratch


def build_python_dir(build):
    """The directory of the interpreter the build configured (MPCAL_PYTHON:
    Debian's, with the packages install-deps.sh installs), so that the pages'
    `python3` is that one and not one earlier on PATH (pyenv's, say)."""
    try:
        with open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8") as cache:
            for line in cache:
                if line.startswith("MPCAL_PYTHON:FILEPATH="):
                    return os.path.dirname(line.split("=", 1)[1].strip())
    except OSError:
        pass
    return ""


def run_block(steps, work, build):
    path = [build, build_python_dir(build), os.environ["PATH"]]
    env = dict(os.environ, PATH=os.pathsep.join(p for p in path if p),
               COLUMNS="100", NO_COLOR="1")
    outputs = []
    for command, _ in steps:
        proc = subprocess.run(["bash", "-c", "{ " + command + "\n} 2>&1"], cwd=work,
                              env=env, stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, timeout=600)
        text = proc.stdout.decode("utf-8", "replace")
        outputs.append([l.rstrip() for l in text.splitlines()])
    return outputs


def ellipsis_at(expected):
    """Index of the first `...` line (indentation allowed), or None."""
    return next((i for i, l in enumerate(expected) if l.strip() == ELLIPSIS), None)


def matches(expected, actual):
    """Whether actual lines match expected ones, `...` standing for any lines."""
    k = ellipsis_at(expected)
    if k is None:
        return expected == actual
    head, tail = expected[:k], expected[k + 1:]
    if actual[:k] != head:
        return False
    for start in range(k, len(actual) + 1):
        if matches(tail, actual[start:]):
            return True
    return False


def shortened(expected, actual):
    """The actual output, shortened as the README's was around its first `...`
    (the lines before and after it kept in number)."""
    k = ellipsis_at(expected)
    if k is None or ellipsis_at(expected[k + 1:]) is not None:
        return actual
    after = len(expected) - k - 1
    if len(actual) <= k + after:
        return actual
    return actual[:k] + [expected[k]] + (actual[len(actual) - after:] if after else [])


def documents(root, given):
    """The pages to run: those given, else README.md and every page under docs/."""
    if given:
        return given
    pages = [os.path.join(root, "README.md")]
    for folder, _, files in sorted(os.walk(os.path.join(root, "docs"))):
        pages += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    return pages


def run_page(page, lines, root, build, check):
    """Runs the blocks of one page; (new lines, blocks run, outputs that differ)."""
    name = os.path.relpath(page, root)
    failures, ran = 0, 0
    new_lines, cursor = [], 0
    scratch = None
    for start, end, skip, cont in parse_blocks(lines):
        if skip:
            continue
        if scratch is None or not cont:
            if scratch is not None:
                scratch.cleanup()
            scratch = scratch_directory(root, build)
        steps = [(c, [l.rstrip() for l in e]) for c, e in split_commands(lines[start:end])]
        outputs = run_block(steps, scratch.name, build)
        ran += 1
        block = []
        for (command, expected), actual in zip(steps, outputs):
            if not matches(expected, actual):
                failures += 1
                if check:
                    print(f"{name}:{start + 1}: `$ {command}` printed:", file=sys.stderr)
                    for l in actual[:40]:
                        print("    " + l, file=sys.stderr)
                    print("  the page shows:", file=sys.stderr)
                    for l in expected[:40]:
                        print("    " + l, file=sys.stderr)
            block.append("$ " + command)
            block.extend(shortened(expected, actual))
        new_lines.extend(lines[cursor:start])
        new_lines.extend(block)
        cursor = end
    new_lines.extend(lines[cursor:])
    if scratch is not None:
        scratch.cleanup()
    return new_lines, ran, failures


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true")
    mode.add_argument("--update", action="store_true")
    mode.add_argument("--marks", action="store_true")
    ap.add_argument("--build", default="build")
    ap.add_argument("--readme", action="append",
                    help="a page to run (repeatable); default README.md and docs/**/*.md")
    args = ap.parse_args()

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    pages = documents(root, args.readme)
    texts = {}
    bad_marks = []
    for page in pages:
        with open(page, encoding="utf-8") as f:
            texts[page] = f.read().split("\n")
        for number, problem in check_marks(texts[page]):
            bad_marks.append(page)
            print(f"{os.path.relpath(page, root)}:{number}: {problem}", file=sys.stderr)
    if args.marks:
        skipped = sum(1 for lines in texts.values() for line in lines if is_skip_mark(line))
        print(f"readme_run: {skipped} skip marks, {len(bad_marks)} without a valid date "
              "and command")
        return 1 if bad_marks else 0

    build = os.path.abspath(args.build)
    if not os.access(os.path.join(build, "mpcal"), os.X_OK):
        sys.exit(f"readme_run: {build}/mpcal not built (make build)")

    failures, ran = 0, 0
    for page in pages:
        new_lines, page_ran, page_failures = run_page(page, texts[page], root, build,
                                                      args.check)
        ran += page_ran
        failures += page_failures
        if args.update and page_failures:
            with open(page, "w", encoding="utf-8") as f:
                f.write("\n".join(new_lines))
    if args.update:
        print(f"readme_run: {len(pages)} pages, {ran} blocks run, {failures} outputs updated")
        return 0
    print(f"readme_run: {len(pages)} pages, {ran} blocks run, {failures} outputs differ "
          f"from the pages, {len(bad_marks)} skip marks without a valid date and command")
    return 1 if failures or bad_marks else 0


if __name__ == "__main__":
    sys.exit(main())
