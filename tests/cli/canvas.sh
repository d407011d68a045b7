#!/usr/bin/env bash
# tessera canvas render: an SVG becomes a PNG quietly; bad input (malformed SVG, missing file, negative size) gives a
# one-line error, a nonzero exit and no output file; unsupported elements are listed once on stderr.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

fail() { echo "canvas.sh: $*"; exit 1; }

cat >"$scratch/ok.svg" <<'SVG'
<svg xmlns="http://www.w3.org/2000/svg" width="40" height="30" viewBox="0 0 20 15">
  <g transform="rotate(10 10 7.5)" fill="orange" stroke="navy" stroke-width="0.5">
    <rect x="2" y="2" width="8" height="6" rx="1"/>
    <path d="M12 3 C15 0 18 6 15 9 S12 14 11 10 z" fill-opacity="0.7"/>
  </g>
</svg>
SVG

# A valid drawing: the file appears, nothing is printed without --stats.
"$tessera" canvas render "$scratch/ok.svg" -o "$scratch/ok.png" >"$scratch/stdout" 2>"$scratch/stderr"
[ -s "$scratch/ok.png" ] || fail "no ok.png"
[ ! -s "$scratch/stdout" ] || fail "stdout is not empty: $(cat "$scratch/stdout")"
[ ! -s "$scratch/stderr" ] || fail "stderr is not empty: $(cat "$scratch/stderr")"
if command -v file >/dev/null; then file "$scratch/ok.png" | grep -q "40 x 30" || fail "ok.png is not 40x30"; fi

# --size, --no-antialias, --background and --stats.
stats=$("$tessera" canvas render "$scratch/ok.svg" -o "$scratch/big.png" --size 80x60 --no-antialias \
          --background '#ffffff' --stats)
grep -qx "width=80" <<<"$stats" || fail "--stats lacks width=80: $stats"
grep -qx "shapes=2" <<<"$stats" || fail "--stats lacks shapes=2: $stats"
[ -s "$scratch/big.png" ] || fail "no big.png"

expect_exit() {  # expect_exit CODES PATTERN COMMAND...: exit code in CODES (e.g. "1" or "1 2"), stderr matches PATTERN
  local codes=$1 pattern=$2; shift 2
  local status=0
  "$@" 2>"$scratch/stderr" >/dev/null || status=$?
  grep -qw -- "$status" <<<"$codes" || { cat "$scratch/stderr"; fail "expected exit $codes, got $status: $*"; }
  grep -q -- "$pattern" "$scratch/stderr" || { cat "$scratch/stderr"; fail "stderr lacks '$pattern': $*"; }
  [ "$(wc -l <"$scratch/stderr")" -le 2 ] || { cat "$scratch/stderr"; fail "the error is not short: $*"; }
}

# A malformed SVG: exit 1, the message names the file and line, and no output file is left behind.
printf '<svg width="10" height="10">\n  <g>\n    <rect width="5" height="5"/>\n</svg>\n' >"$scratch/bad.svg"
expect_exit 1 "tessera: error: .*bad.svg:4:1: expected </g> to close <g> from line 2" \
  "$tessera" canvas render "$scratch/bad.svg" -o "$scratch/bad.png"
[ ! -e "$scratch/bad.png" ] || fail "bad.png was written"
printf '<svg width="10" height="10"><path d="M0 0 L 5"/></svg>' >"$scratch/badpath.svg"
expect_exit 1 "badpath.svg:1:" "$tessera" canvas render "$scratch/badpath.svg" -o "$scratch/badpath.png"
[ ! -e "$scratch/badpath.png" ] || fail "badpath.png was written"
ls "$scratch" | grep -q tmp && fail "a temporary file was left behind"

# A missing file, a negative size, a bad background.
expect_exit 1 "tessera: error: .*missing.svg" "$tessera" canvas render "$scratch/missing.svg" -o "$scratch/m.png"
[ ! -e "$scratch/m.png" ] || fail "m.png was written"
expect_exit "1 2" "size" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/neg.png" --size -5x5
expect_exit "1 2" "size" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/neg.png" --size=-5x5
[ ! -e "$scratch/neg.png" ] || fail "neg.png was written"
# Malformed values are usage errors (exit 2), found before anything is read or written.
expect_exit 2 "background" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/bg.png" --background 2,0,0
expect_exit 2 "background.*whit" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/bg.png" --background whit
expect_exit 2 "size" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/bg.png" --size 800
expect_exit 2 "tolerance" "$tessera" canvas render "$scratch/ok.svg" -o "$scratch/bg.png" --tolerance 0
expect_exit 2 "size" "$tessera" canvas render "$scratch/missing.svg" -o "$scratch/bg.png" --size 8x
[ ! -e "$scratch/bg.png" ] || fail "bg.png was written"
expect_exit 2 "" "$tessera" canvas render "$scratch/ok.svg"

# Colors by name (as SVG spells them), #rrggbb and r,g,b; --srgb encodes with the sRGB formula: a linear gray of 0.5
# is 128 in the file without it and 188 with it; the whole picture is checked against its linear floats (PFM).
py=/usr/bin/python3 check="$(dirname "$0")/srgb_check.py"
printf '<svg width="16" height="8"><rect x="8" width="8" height="8" fill="#336699"/></svg>' >"$scratch/half.svg"
"$tessera" canvas render "$scratch/half.svg" -o "$scratch/white.png" --background white
"$py" "$check" pixel "$scratch/white.png" 0 0 1,1,1 || fail "--background white"
"$tessera" canvas render "$scratch/half.svg" -o "$scratch/blue.png" --background cornflowerblue
"$py" -c "import sys; from PIL import Image; sys.exit(Image.open(sys.argv[1]).getpixel((0, 0)) != (100, 149, 237, 255))" \
  "$scratch/blue.png" || fail "--background cornflowerblue is not SVG's (100, 149, 237)"
"$tessera" canvas render "$scratch/half.svg" -o "$scratch/gray.png" --background 0.5,0.5,0.5
"$py" -c "import sys; from PIL import Image; sys.exit(Image.open(sys.argv[1]).getpixel((0, 0)) != (128, 128, 128, 255))" \
  "$scratch/gray.png" || fail "a linear 0.5 gray is not 128 without --srgb"
"$tessera" canvas render "$scratch/half.svg" -o "$scratch/gray_srgb.png" --background 0.5,0.5,0.5 --srgb
"$py" "$check" pixel "$scratch/gray_srgb.png" 0 0 0.5,0.5,0.5 || fail "--srgb gray"
"$tessera" canvas render "$scratch/ok.svg" -o "$scratch/ok.pfm" --background '#ffffff'
"$tessera" canvas render "$scratch/ok.svg" -o "$scratch/ok_srgb.png" --background '#ffffff' --srgb
"$py" "$check" pfm "$scratch/ok.pfm" "$scratch/ok_srgb.png" || fail "--srgb picture"
stats=$("$tessera" canvas render "$scratch/ok.svg" -o "$scratch/ok.png" --stats)
for key in width height pixels shapes warnings seconds read_s compute_s write_s total_s; do
  grep -q "^$key=" <<<"$stats" || fail "--stats lacks $key: $stats"
done
grep -qx "pixels=1200" <<<"$stats" || fail "pixels is not 40 x 30: $stats"

# Unsupported elements: drawn without them, listed once on stderr.
printf '<svg width="10" height="10"><text>a</text><text>b</text><rect width="5" height="5"/></svg>' \
  >"$scratch/text.svg"
"$tessera" canvas render "$scratch/text.svg" -o "$scratch/text.png" 2>"$scratch/stderr"
grep -qx "tessera: warning: unsupported SVG elements ignored: text (2)" "$scratch/stderr" || fail "no warning"
[ "$(wc -l <"$scratch/stderr")" -eq 1 ] || fail "the warning is repeated"
[ -s "$scratch/text.png" ] || fail "no text.png"
echo "cli canvas: ok"
