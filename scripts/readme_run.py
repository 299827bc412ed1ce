#!/usr/bin/env python3
"""Runs the commands shown in README.md and compares (or replaces) their output.

The README shows commands as `$ command` lines inside fenced blocks, each
followed by what it printed. This script runs every block in a scratch
directory of its own (with the repository's `tests/`, `bench/` and the build's
`mpcal` reachable, so the paths a clone has work), feeding each command to
bash with stderr merged into stdout, and then either checks that the README
shows what the commands print today (`--check`, run by CI) or writes the new
output into the README (`--update`).

  - A line `...` in the README's output stands for any number of lines (used
    to shorten long outputs); --update keeps the same number of lines before
    and after it.
  - A block is skipped when the line before its opening fence is
    `<!-- readme-run: skip -->` (timings, benches that take minutes).

  scripts/readme_run.py --check  [--build build] [--readme README.md]
  scripts/readme_run.py --update [--build build] [--readme README.md]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SKIP_MARK = "<!-- readme-run: skip -->"
ELLIPSIS = "..."


def parse_blocks(lines):
    """Yields (start, end, skip) line ranges of fenced blocks holding `$ ` lines."""
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            body = lines[i + 1:j]
            if any(l.startswith("$ ") for l in body):
                skip = i > 0 and lines[i - 1].strip() == SKIP_MARK
                yield i + 1, j, skip
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


def run_block(steps, root, build):
    with tempfile.TemporaryDirectory(prefix="mpcal_readme_") as work:
        for name in ("tests", "bench", "examples"):
            os.symlink(os.path.join(root, name), os.path.join(work, name))
        os.symlink(build, os.path.join(work, "build"))
        env = dict(os.environ, PATH=build + os.pathsep + os.environ["PATH"],
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


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true")
    mode.add_argument("--update", action="store_true")
    ap.add_argument("--build", default="build")
    ap.add_argument("--readme", default="README.md")
    args = ap.parse_args()

    root = os.path.dirname(os.path.abspath(args.readme))
    build = os.path.abspath(args.build)
    if not os.access(os.path.join(build, "mpcal"), os.X_OK):
        sys.exit(f"readme_run: {build}/mpcal not built (make build)")
    with open(args.readme, encoding="utf-8") as f:
        lines = f.read().split("\n")

    failures, ran = 0, 0
    new_lines, cursor = [], 0
    for start, end, skip in parse_blocks(lines):
        if skip:
            continue
        steps = [(c, [l.rstrip() for l in e]) for c, e in split_commands(lines[start:end])]
        outputs = run_block(steps, root, build)
        ran += 1
        block = []
        for (command, expected), actual in zip(steps, outputs):
            if not matches(expected, actual):
                failures += 1
                if args.check:
                    print(f"README.md:{start + 1}: `$ {command}` printed:", file=sys.stderr)
                    for l in actual[:40]:
                        print("    " + l, file=sys.stderr)
                    print("  the README shows:", file=sys.stderr)
                    for l in expected[:40]:
                        print("    " + l, file=sys.stderr)
            block.append("$ " + command)
            block.extend(shortened(expected, actual))
        new_lines.extend(lines[cursor:start])
        new_lines.extend(block)
        cursor = end
    new_lines.extend(lines[cursor:])

    if args.update:
        with open(args.readme, "w", encoding="utf-8") as f:
            f.write("\n".join(new_lines))
        print(f"readme_run: {ran} blocks run, {failures} outputs updated")
        return 0
    print(f"readme_run: {ran} blocks run, {failures} outputs differ from the README")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
