#!/usr/bin/env python3
"""Every citation of the method document points at a section it has.

Source comments, --help texts, the README and the benches cite the
mathematics as "docs/method.md §N" or "§N.M". Fails when a cited section is
not a heading of docs/method.md ("## N." or "### N.M"), or when a citation
names a method file that is not in the repository (the document's name
without its folder).

usage: method_citations.py PROJECT_ROOT
"""
import pathlib
import re
import sys

FOLDERS = ["apps", "bench", "docs", "examples", "fuzz", "include", "scripts", "src", "tests"]
SUFFIXES = {".h", ".cc", ".cpp", ".py", ".sh", ".md", ".txt", ".cmake"}
CITATION = re.compile(r"docs/method\.md((?:\s*(?:§|sections?\s)\s*[\d.]+(?:\s*(?:,|and)\s*§?\s*[\d.]+)*)?)")
NUMBER = re.compile(r"\d+(?:\.\d+)?")
# "METHOD.md" on its own, in upper case: not the repository's document (a
# relative link to method.md inside docs/ is the document itself).
STRAY = re.compile(r"(?<![\w/])" + "METHOD" + r"\.md")
HEADING = re.compile(r"^#{2,3} (\d+(?:\.\d+)?)\.? ")


def sources(root):
    yield root / "README.md"
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.is_file() and path.suffix in SUFFIXES and "data" not in path.parts:
                yield path


def main():
    root = pathlib.Path(sys.argv[1])
    method = root / "docs" / "method.md"
    if not method.is_file():
        print("FAIL docs/method.md is missing")
        return 1
    sections = set()
    for line in method.read_text(encoding="utf-8").splitlines():
        m = HEADING.match(line)
        if m:
            sections.add(m.group(1))
    failures, citations = 0, 0
    this = pathlib.Path(__file__).resolve()
    for path in sources(root):
        if path.resolve() == this:
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        # Citations may wrap onto the next line of a comment.
        flat = re.sub(r"\n\s*(?://+|#+|\*)?\s*", " ", text)
        for m in CITATION.finditer(flat):
            citations += 1
            for number in NUMBER.findall(m.group(1)):
                if number not in sections:
                    print(f"FAIL {path.relative_to(root)}: cites docs/method.md §{number}, "
                          "which is not a section of it")
                    failures += 1
        for number, line in enumerate(text.splitlines(), 1):
            if STRAY.search(line) and path != method:
                print(f"FAIL {path.relative_to(root)}:{number}: cites a method file that is "
                      "not in the repository; cite docs/method.md")
                failures += 1
    print(f"{citations} citations of docs/method.md ({len(sections)} sections), "
          f"{failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
