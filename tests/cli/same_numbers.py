#!/usr/bin/env python3
"""Exits 0 when two mpcal result files (JSON) hold the same numbers.

  same_numbers.py A.json B.json [KEY.PATH ...]

Every value must be equal (numbers exactly) except at the dotted key paths
given, which name what legitimately differs (the input's name, say).
"""
import json
import sys


def diff(a, b, path, ignored, out):
    if path in ignored:
        return
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            sub = f"{path}.{k}" if path else k
            if sub in ignored:
                continue
            if k not in a or k not in b:
                out.append(f"{sub}: only in {'the first' if k in a else 'the second'}")
            else:
                diff(a[k], b[k], sub, ignored, out)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            diff(x, y, f"{path}[{i}]", ignored, out)
    elif a != b:
        out.append(f"{path}: {a!r} != {b!r}")


def main():
    first, second, *ignored = sys.argv[1:]
    with open(first) as f:
        a = json.load(f)
    with open(second) as f:
        b = json.load(f)
    out = []
    diff(a, b, "", set(ignored), out)
    for line in out[:20]:
        print(line)
    print(f"{len(out)} difference(s)")
    sys.exit(1 if out else 0)


if __name__ == "__main__":
    main()
