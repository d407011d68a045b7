#!/usr/bin/env bash
# tessera color convert: known conversions (exact output), stdin rows, hue units, the bad-row error (exit 1, message
# naming the line, nothing of the bad row written), usage errors (exit 2, --values included) and --stats.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

expect_output() {  # expect_output EXPECTED COMMAND...: stdout must equal EXPECTED exactly
  local expected=$1; shift
  local got
  got=$("$@")
  [ "$got" = "$expected" ] || { printf 'expected:\n%s\ngot:\n%s\nfrom: %s\n' "$expected" "$got" "$*"; exit 1; }
}
convert() { "$tessera" color convert "$@"; }

expect_output "30,1,1" convert --from rgb --to hsv --values 1,0.5,0
expect_output "0,0.5,1" convert --from rgb --to hls --values 1,0,0
expect_output "0,0,1" convert --from hsv --to rgb --values 240,1,1
expect_output "0,1,1" convert --from hsv --to rgb --hue turns --values 0.5,1,1
expect_output "1,1,0" convert --from hsv --to rgb --hue radians --values 1.0471975511965976,1,1
expect_output "0,0,0,1" convert --from rgb --to cmyk --values 0,0,0
expect_output "0,1,1,0.5" convert --from rgb --to cmyk --values 0.5,0,0
expect_output "0.362,-0.18414,0.01982" convert --from rgb --to yiq --values 0.2,0.4,0.6
expect_output "0.735356983,0,1" convert --from rgb --to srgb --values 0.5,0,1
expect_output "0.412390799,0.212639006,0.0193308187" convert --from rgb --to xyz --values 1,0,0
expect_output "330,1,1" convert --from hsv --to hsv --values -30,1,1

# CSV rows on stdin: one output row per input row, blank rows kept, white and black in xyY (black takes D65).
expect_output "$(printf '0,1,1\n120,1,1\n\n0,0,0.5')" convert --from rgb --to hsv < <(printf '1,0,0\n0,1,0\n\n0.5,0.5,0.5\n')
expect_output "$(printf '0.3127,0.329,1\n0.3127,0.329,0')" convert --from rgb --to xyy < <(printf '1,1,1\n0,0,0\n')
# A round trip through every model gives the input back (to the 9 printed digits).
for model in cmy cmyk hsv hls yiq xyz xyy srgb; do
  expect_output "0.250000,0.500000,0.750000" bash -c "
    '$tessera' color convert --from rgb --to $model --values 0.25,0.5,0.75 |
      '$tessera' color convert --from $model --to rgb | awk -F, '{ printf \"%.6f,%.6f,%.6f\\n\", \$1, \$2, \$3 }'"
done

# A bad row: exit 1, "tessera: error: stdin:LINE: ...", the rows before it written, nothing of the bad one.
status=0
printf '1,0,0\n1,2\n0,1,0\n' | convert --from rgb --to hls >"$scratch/out" 2>"$scratch/err" || status=$?
[ "$status" -eq 1 ] || { echo "bad row: expected exit 1, got $status"; exit 1; }
[ "$(cat "$scratch/err")" = "tessera: error: stdin:2: expected 3 comma-separated numbers, got '1,2'" ] ||
  { echo "bad row message:"; cat "$scratch/err"; exit 1; }
[ "$(cat "$scratch/out")" = "0,0.5,1" ] || { echo "bad row output:"; cat "$scratch/out"; exit 1; }
status=0
printf '0.1,0.2,0.3\n0.1,x,0.3\n' | convert --from rgb --to cmyk >/dev/null 2>"$scratch/err" || status=$?
[ "$status" -eq 1 ] && grep -q "stdin:2: expected 3 comma-separated numbers, got '0.1,x,0.3'" "$scratch/err" ||
  { echo "non-number row: exit $status"; cat "$scratch/err"; exit 1; }
# A value the model cannot convert names the row: xyY with y = 0 and Y != 0.
status=0
printf '0.3,0.3,1\n0.3,0,1\n' | convert --from xyy --to rgb >/dev/null 2>"$scratch/err" || status=$?
[ "$status" -eq 1 ] && grep -q "tessera: error: stdin:2: " "$scratch/err" ||
  { echo "xyY row: exit $status"; cat "$scratch/err"; exit 1; }
# --values is an option: a malformed one is a usage error (exit 2) that says what was expected.
for case in "cmyk 0,0,0 expected 4 comma-separated numbers" "rgb 1,x,0 expected 3 comma-separated numbers" \
            "xyy 0.3,0,1 --values: " "rgb 5,-1,0 rgb components must be in \[0, 1\]" \
            "hsv 30,1.5,1 hsv components must be in \[0, 1\] (but the hue)" "cmyk 0,0,0,2 cmyk components must be"; do
  read -r model values pattern <<<"$case"
  status=0
  convert --from "$model" --to rgb --values "$values" >/dev/null 2>"$scratch/err" || status=$?
  [ "$status" -eq 2 ] && grep -q "tessera: error: .*$pattern" "$scratch/err" ||
    { echo "--values $values: exit $status"; cat "$scratch/err"; exit 1; }
done
# Model names are matched without case; an unknown one lists the names, never internal numbers.
expect_output "30,1,1" convert --from RGB --to Hsv --values 1,0.5,0
status=0
convert --from lab --to rgb --values 1,2,3 2>"$scratch/err" >/dev/null || status=$?
[ "$status" -eq 2 ] && grep -q "rgb,cmy,cmyk,hsv" "$scratch/err" && ! grep -q -- "->" "$scratch/err" ||
  { echo "unknown model: exit $status"; cat "$scratch/err"; exit 1; }
# --stats after the rows: how many colors were converted, the conversion time and the whole command's.
expect_output "$(printf '0,1,1\n\n120,1,1\ncolors=2')" bash -c \
  "printf '1,0,0\n\n0,1,0\n' | '$tessera' color convert --from rgb --to hsv --stats | grep -v '_s='"
stats=$(convert --from rgb --to hsv --values 1,0,0 --stats)
grep -q "^compute_s=" <<<"$stats" && grep -q "^total_s=" <<<"$stats" || { echo "--stats: $stats"; exit 1; }

# Usage errors: exit 2.
for args in "convert --from lab --to rgb --values 1,2,3" "convert --from rgb" "convert --from rgb --to hsv --hue grad" ""; do
  status=0
  # shellcheck disable=SC2086
  "$tessera" color $args </dev/null >/dev/null 2>&1 || status=$?
  [ "$status" -eq 2 ] || { echo "usage error 'color $args': expected exit 2, got $status"; exit 1; }
done
echo "cli color: ok"
