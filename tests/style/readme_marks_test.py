#!/usr/bin/env python3
"""The README's skipped output blocks say what made them and when.

A block the README checker skips (scripts/readme_run.py) is never compared
with the program, so its mark must name the date and the command that made
it. Checks the rule on small examples, then on the repository's README.

usage: readme_marks_test.py PROJECT_ROOT
"""
import datetime
import importlib.util
import os
import pathlib
import subprocess
import sys
import tempfile


def load_checker(root):
    spec = importlib.util.spec_from_file_location(
        "readme_run", root / "scripts" / "readme_run.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_check(root, text):
    """scripts/readme_run.py --check on a README of `text` beside a stand-in
    build: its exit status and what it printed."""
    with tempfile.TemporaryDirectory() as tmp:
        build = pathlib.Path(tmp) / "build"
        build.mkdir()
        (build / "mpcal").write_text("#!/bin/sh\n")
        os.chmod(build / "mpcal", 0o755)
        readme = pathlib.Path(tmp) / "README.md"
        readme.write_text(text, encoding="utf-8")
        proc = subprocess.run([sys.executable, str(root / "scripts" / "readme_run.py"),
                               "--check", "--build", str(build), "--readme", str(readme)],
                              capture_output=True, text=True, check=False)
        return proc.returncode, proc.stdout + proc.stderr


def main():
    root = pathlib.Path(sys.argv[1])
    rr = load_checker(root)
    today = datetime.date(2026, 11, 25)
    fence = "```"
    good = "<!-- readme-run: skip; made 2026-11-23 by bash bench/noise_bench.sh build 3 8 400 -->"
    cases = [
        ("named date and command", [good, fence, "$ x", fence], 0),
        ("bare mark", ["<!-- readme-run: skip -->", fence, fence], 1),
        ("no command", ["<!-- readme-run: skip; made 2026-11-23 by  -->", fence], 1),
        ("no date", ["<!-- readme-run: skip; by make fuzz -->", fence], 1),
        ("not a date", ["<!-- readme-run: skip; made 2026-13-40 by make fuzz -->", fence], 1),
        ("a date after today", ["<!-- readme-run: skip; made 2026-12-01 by make fuzz -->",
                                fence], 1),
        ("not before a fence", [good, "", fence], 1),
        ("last line", ["text", good], 1),
        ("an unknown mark", ["<!-- readme-run: keep -->", fence], 1),
        ("a continuation", ["<!-- readme-run: continue -->", fence, "$ x", fence], 0),
        ("a continuation not before a fence", ["<!-- readme-run: continue -->", ""], 1),
        ("no mark at all", ["text", fence, "$ x", fence], 0),
    ]
    failures = 0
    for name, lines, expected in cases:
        got = len(rr.check_marks(lines, today))
        if got != expected:
            print(f"FAIL {name}: {got} problems, expected {expected}")
            failures += 1
    # A malformed mark still keeps its block from running; a continuation
    # is told apart.
    blocks = list(rr.parse_blocks(["<!-- readme-run: skip -->", fence, "$ x", fence,
                                   "<!-- readme-run: continue -->", fence, "$ y", fence]))
    if blocks != [(2, 3, True, False), (6, 7, False, True)]:
        print(f"FAIL a bare mark skips its block, a continuation continues: {blocks}")
        failures += 1

    # A continuation sees the files of the block before it; the next block
    # starts afresh; a bare skip mark fails the check.
    continued = ("```\n$ echo made > f.txt\n```\n"
                 "<!-- readme-run: continue -->\n```\n$ cat f.txt\nmade\n```\n"
                 "```\n$ cat f.txt 2>/dev/null || echo fresh\nfresh\n```\n")
    status, out = run_check(root, continued)
    if status != 0:
        print(f"FAIL a continuation runs in the directory before it:\n{out}")
        failures += 1
    status, out = run_check(root, "<!-- readme-run: skip -->\n```\n$ true\n```\n")
    if status == 0:
        print(f"FAIL --check passes a skip mark without date and command:\n{out}")
        failures += 1

    marks = 0
    pages = rr.documents(str(root), None)
    for page in pages:
        lines = pathlib.Path(page).read_text(encoding="utf-8").split("\n")
        for number, problem in rr.check_marks(lines):
            print(f"FAIL {os.path.relpath(page, root)}:{number}: {problem}")
            failures += 1
        marks += sum(1 for line in lines if rr.is_skip_mark(line))
    print(f"{len(cases) + 3} examples, {marks} skip marks in {len(pages)} pages, "
          f"{failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
