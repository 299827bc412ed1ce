#!/usr/bin/env bash
# Renders an mpcal report in headless Chromium and checks what a reader sees.
#
#   render_test.sh --out DIR --figures N --sections a,b,... [--height PX] \
#                  -- COMMAND ARGS...
#
# COMMAND must write the report to the path given by the token @OUT@ in its
# arguments (replaced by DIR/report.html). Then:
#   1. the rendered DOM (--dump-dom) has exactly N <figure> elements, each
#      with one <svg>, exactly the listed <section> ids, and no <img>,
#      <script>, <link> or <iframe>;
#   2. a screenshot at a laptop's width (1280 px) is a PNG that is not blank:
#      enough distinct colours and ink, in the top screen and overall;
#   3. Chromium logged no console message (no script error, no failed load).
# Screenshots stay in DIR for a person to look at (report.png, top.png).
#
# Chromium is /usr/bin/chromium (or $CHROMIUM); if it is missing the test
# FAILS, saying how to install it: it never skips silently.
set -u

out=""; figures=""; sections=""; height=9000
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --figures) figures=$2; shift 2 ;;
    --sections) sections=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    *) echo "render_test.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
[ "${1:-}" = "--" ] && shift
if [ -z "$out" ] || [ -z "$figures" ] || [ -z "$sections" ] || [ $# -eq 0 ]; then
  echo "usage: render_test.sh --out DIR --figures N --sections a,b -- COMMAND ARGS (@OUT@)" >&2
  exit 2
fi

chromium=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ]; then
  echo "FAIL: Chromium not found at $chromium: the report's browser test needs it." \
       "Install it with: scripts/install-deps.sh (Debian package 'chromium')," \
       "or point CHROMIUM at a Chromium binary."
  exit 1
fi
if ! command -v python3 >/dev/null; then
  echo "FAIL: python3 is needed to check the rendered page"; exit 1
fi

mkdir -p "$out" || exit 1
html="$out/report.html"
rm -f "$html" "$out/report.png" "$out/top.png" "$out/dom.html"
args=()
for a in "$@"; do args+=("${a//@OUT@/$html}"); done
if ! "${args[@]}" >"$out/generate.log" 2>&1; then
  echo "FAIL: the command that writes the report failed: ${args[*]}"
  cat "$out/generate.log"; exit 1
fi
[ -s "$html" ] || { echo "FAIL: no report at $html"; exit 1; }

profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
url="file://$(cd "$(dirname "$html")" && pwd)/$(basename "$html")"
browse() {
  timeout 90 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic \
    --no-first-run --disable-background-networking --disable-component-update \
    --disable-sync --hide-scrollbars --user-data-dir="$profile" \
    --enable-logging=stderr --v=0 "$@" "$url"
}
browse --dump-dom >"$out/dom.html" 2>"$out/dom.log" ||
  { echo "FAIL: chromium --dump-dom failed"; tail -5 "$out/dom.log"; exit 1; }
browse --screenshot="$out/report.png" --window-size=1280,"$height" 2>"$out/shot.log" ||
  { echo "FAIL: chromium --screenshot failed"; tail -5 "$out/shot.log"; exit 1; }
browse --screenshot="$out/top.png" --window-size=1280,900 2>"$out/top.log" ||
  { echo "FAIL: chromium --screenshot (top) failed"; tail -5 "$out/top.log"; exit 1; }

python3 - "$out" "$figures" "$sections" <<'PY'
import re, struct, sys, zlib

out, want_figures, want_sections = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(",")
failures = []

# 1. The DOM as the browser built it.
dom = open(f"{out}/dom.html", encoding="utf-8").read()
figs = re.findall(r"<figure\b.*?</figure>", dom, re.S)
if len(figs) != want_figures:
    failures.append(f"{len(figs)} figures rendered, expected {want_figures}")
for i, f in enumerate(figs):
    if len(re.findall(r"<svg\b", f)) != 1 or "</svg>" not in f:
        failures.append(f"figure {i + 1} does not hold exactly one complete <svg>")
svgs = len(re.findall(r"<svg\b", dom))
if svgs != want_figures:
    failures.append(f"{svgs} <svg> elements, expected {want_figures}")
found = re.findall(r'<section id="([a-z]+)"', dom)
if sorted(found) != sorted(want_sections):
    failures.append(f"sections {found}, expected {want_sections}")
for tag in ("img", "script", "link", "iframe", "object", "embed"):
    if re.search(rf"<{tag}\b", dom):
        failures.append(f"the page has a <{tag}>: it must be self-contained")
if re.search(r"https?://", dom):
    failures.append("the page mentions an http(s):// URL")
print(f"DOM: {len(figs)} figures, {svgs} svg, sections {found}")

# 2. The screenshots: decode the PNG (8-bit RGB/RGBA, what Chromium writes).
def decode_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or color not in (2, 6) or interlace:
                raise ValueError(f"unsupported PNG (depth {depth}, colour {color})")
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows

def check_png(path, min_colours, min_ink):
    try:
        w, h, bpp, rows = decode_png(path)
    except Exception as e:  # noqa: BLE001 - any decoding failure is a test failure
        failures.append(f"{path}: {e}")
        return
    # Ink is counted over the page's content (down to its last inked row),
    # so that a short page in a tall window is not taken for a blank one.
    colours, ink, last, per_row = set(), 0, 0, w // 2
    for y in range(0, h, 2):  # every other row and pixel: plenty, and fast
        r = rows[y]
        row_ink = 0
        for x in range(0, w * bpp, 2 * bpp):
            px = r[x:x + 3]
            colours.add(px)
            if px[0] + px[1] + px[2] < 3 * 235:
                row_ink += 1
        if row_ink:
            ink += row_ink
            last = y
    frac = ink / max(per_row * (last // 2 + 1), 1)
    print(f"{path}: {w}x{h}, content {last + 1} px high, {len(colours)} colours, "
          f"{100 * frac:.1f}% ink")
    if w != 1280:
        failures.append(f"{path}: width {w}, expected 1280")
    if len(colours) < min_colours:
        failures.append(f"{path}: only {len(colours)} colours: blank or unstyled")
    if frac < min_ink:
        failures.append(f"{path}: {100 * frac:.2f}% ink: the page looks blank")

check_png(f"{out}/top.png", 16, 0.01)
check_png(f"{out}/report.png", 16 if want_figures else 8, 0.005)

# 3. Console messages: the page has no script, so any is a fault.
for log in ("dom.log", "shot.log", "top.log"):
    for line in open(f"{out}/{log}", encoding="utf-8", errors="replace"):
        if ":CONSOLE" in line or "Failed to load resource" in line:
            failures.append(f"console: {line.strip()}")

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
PY
