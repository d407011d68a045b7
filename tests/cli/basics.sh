#!/usr/bin/env bash
# The CLI's common contract: help lists every command, usage errors exit 2, runtime errors exit 1 with
# "tessera: error:", and the gallery writes pictures plus an index.html.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

help=$("$tessera" --help)
for command in demo gallery canvas color mesh curve patch fractal; do
  grep -q "^  $command" <<<"$help" || { echo "--help does not list '$command'"; exit 1; }
done
"$tessera" --version | grep -q '^tessera '

expect_exit() {  # expect_exit CODE PATTERN COMMAND...: runs COMMAND, checks its exit code and that stderr matches
  local code=$1 pattern=$2; shift 2
  local status=0
  "$@" 2>"$scratch/stderr" >/dev/null || status=$?
  [ "$status" -eq "$code" ] || { echo "expected exit $code, got $status: $*"; cat "$scratch/stderr"; exit 1; }
  grep -q -- "$pattern" "$scratch/stderr" || { echo "stderr lacks '$pattern': $*"; cat "$scratch/stderr"; exit 1; }
}
# A bare tessera lists the commands; unknown commands are named, with the nearest one suggested.
expect_exit 2 "fractal  *Fractals" "$tessera"
expect_exit 2 "tessera: error: unknown command 'no-such-command'" "$tessera" no-such-command
expect_exit 2 "unknown command 'frobnicate'" "$tessera" frobnicate
expect_exit 2 "did you mean 'fractal'" "$tessera" fractl
expect_exit 2 "unknown command 'mesh subdvide' (did you mean 'mesh subdivide'?)" "$tessera" mesh subdvide x.obj
expect_exit 2 "'tessera fractal' needs a subcommand: mandelbrot, julia" "$tessera" fractal
expect_exit 2 "'tessera mesh' needs a subcommand: info" "$tessera" mesh --stats
# CLI11's own parse errors carry the same prefix and exit 2.
expect_exit 2 "tessera: error: .*no-such-option" "$tessera" gallery --no-such-option
expect_exit 2 "tessera: error: " "$tessera" gallery --threads -3
expect_exit 2 "tessera: error: .*--scheme" "$tessera" mesh subdivide x.obj -o y.obj --scheme cubic
# Malformed values are usage errors (exit 2), not runtime errors.
expect_exit 2 "tessera: error: --size: expected WIDTHxHEIGHT, got .800." "$tessera" fractal mandelbrot -o "$scratch/m.png" --size 800
expect_exit 2 "tessera: error: .*--progress" "$tessera" gallery --only 01 -o "$scratch/g" --progress loud
# --help shows choices by name, never the internal numbers behind them (CLI11's CheckedTransformer printed
# {catmull-clark->2,...}).
for words in "mesh subdivide" "mesh smooth" "mesh normals" "raster" "trace" "render" "volume render" "fractal mandelbrot" \
             "canvas render" "patch" "curve" "color convert"; do
  # shellcheck disable=SC2086
  help=$("$tessera" $words --help)
  if grep -E -- '->[0-9]' <<<"$help"; then echo "'tessera $words --help' shows internal enum numbers"; exit 1; fi
  grep -q -- "--progress" <<<"$help" || { echo "'tessera $words --help' lacks --progress"; exit 1; }
  grep -q -- "--stats" <<<"$help" || { echo "'tessera $words --help' lacks --stats"; exit 1; }
done
# Floating-point options refuse NaN and infinities (CLI11's range checks let NaN through).
expect_exit 2 "expected a finite number, got 'nan'" "$tessera" volume render sphere:8 -o "$scratch/nan.png" --fovy nan
expect_exit 2 "expected a finite number, got 'inf'" "$tessera" volume render sphere:8 -o "$scratch/inf.png" --step inf
[ ! -e "$scratch/nan.png" ] && [ ! -e "$scratch/inf.png" ] || { echo "a picture was written"; exit 1; }
expect_exit 1 "tessera: error:" "$tessera" gallery -o /proc/forbidden/gallery

"$tessera" gallery --only 01 -o "$scratch/gallery" >/dev/null

# --progress plain prints one line per phase (start, 10% steps, done) for batch logs; --quiet and none print nothing.
"$tessera" volume isosurface sphere:24 --iso 0 -o "$scratch/ball.ply" >/dev/null
"$tessera" trace "$scratch/ball.ply" -o "$scratch/ball.png" --size 32x32 --progress plain 2>"$scratch/progress" >/dev/null
grep -q "^building BVH: started$" "$scratch/progress" || { echo "no plain progress start line"; cat "$scratch/progress"; exit 1; }
grep -q "^building BVH: done in [0-9.]* s$" "$scratch/progress" || { echo "no plain progress end line"; exit 1; }
for quiet in "--quiet" "--progress none"; do
  # shellcheck disable=SC2086
  "$tessera" trace "$scratch/ball.ply" -o "$scratch/ball.png" --size 32x32 $quiet 2>"$scratch/progress" >/dev/null
  [ ! -s "$scratch/progress" ] || { echo "$quiet printed progress"; cat "$scratch/progress"; exit 1; }
done

# Every command prints --stats, with total_s.
stats_of() {  # stats_of COMMAND...: runs it with --stats; checks that it ends in key=value lines, total_s the last
  local out
  out=$("$@" --stats) || { echo "failed: $*"; exit 1; }
  tail -n 1 <<<"$out" | grep -Eq '^total_s=[0-9.e-]+$' || { echo "no total_s at the end from: $*"; echo "$out"; exit 1; }
  [ "$(grep -Ec '^[a-z_0-9]+=' <<<"$out")" -ge 2 ] || { echo "no figures besides total_s from: $*"; echo "$out"; exit 1; }
}
cd "$scratch"
stats_of "$tessera" mesh info ball.ply
stats_of "$tessera" mesh convert ball.ply -o ball.obj
stats_of "$tessera" mesh normals ball.obj -o normals.obj
stats_of "$tessera" mesh smooth ball.obj -o smooth.obj --method laplacian --iterations 2
stats_of "$tessera" mesh triangulate ball.obj -o tri.obj
stats_of "$tessera" mesh subdivide ball.obj -o sub.obj --scheme loop
stats_of "$tessera" volume info sphere:16
stats_of "$tessera" volume slice sphere:16 -o slice.png
stats_of "$tessera" volume contour sphere:16 -o contour.svg
stats_of "$tessera" volume render sphere:16 -o render.png --size 16x16
stats_of "$tessera" volume isosurface sphere:16 -o iso.ply
stats_of "$tessera" raster ball.ply -o raster.png --size 32x32
stats_of "$tessera" trace ball.ply -o trace.png --size 32x32
stats_of "$tessera" render whitted -o whitted.png --size 32x24 --spp 1
stats_of "$tessera" fractal mandelbrot -o m.png --size 32x32
stats_of "$tessera" fractal koch -o k.png
stats_of "$tessera" curve --points 0,0,1,2,3,0 -o c.png
stats_of "$tessera" color convert --from rgb --to hsv --values 1,0.5,0
stats_of "$tessera" gallery --only 01 -o g2
cd - >/dev/null
[ -s "$scratch/gallery/index.html" ] || { echo "no index.html"; exit 1; }
ls "$scratch"/gallery/*.png >/dev/null

# Issue 24, class 4: a write interrupted by SIGTERM or SIGINT leaves no temporary, and the exit status reports the
# signal. The writer is frozen (SIGSTOP) as soon as its temporary appears, so the signal always lands mid-write.
for sig in TERM INT; do
  rm -rf "$scratch/sig" && mkdir -p "$scratch/sig"
  # A background job of a non-interactive shell ignores SIGINT; `set -m` gives it default signal handling.
  set -m
  "$tessera" mesh subdivide "$scratch/ball.ply" -o "$scratch/sig/out.obj" --scheme loop --levels 4 --quiet &
  pid=$!
  set +m
  for _ in $(seq 2000); do
    compgen -G "$scratch/sig/out.obj.tmp-*" >/dev/null && break
    sleep 0.01
  done
  kill -STOP "$pid"
  compgen -G "$scratch/sig/out.obj.tmp-*" >/dev/null || { echo "SIG$sig: the write never started"; exit 1; }
  kill "-$sig" "$pid"
  kill -CONT "$pid"
  status=0
  wait "$pid" || status=$?
  expected=$((128 + $(kill -l "$sig")))
  [ "$status" -eq "$expected" ] || { echo "SIG$sig: exit status $status, expected $expected"; exit 1; }
  leftover=$(ls -A "$scratch/sig")
  [ -z "$leftover" ] || { echo "SIG$sig left files behind: $leftover"; exit 1; }
done

# Issue 24, class 5: clear messages. A folder given where a file is expected says so (was std::bad_alloc or a JSON
# syntax error), with exit 1.
mkdir -p "$scratch/folder.obj" "$scratch/folder.svg" "$scratch/folder.nrrd" "$scratch/folder.json" "$scratch/folder.bpt"
expect_exit 1 "'$scratch/folder.obj': is a directory, expected a file" "$tessera" mesh info "$scratch/folder.obj"
expect_exit 1 "is a directory, expected a file" "$tessera" canvas render "$scratch/folder.svg" -o "$scratch/x.png"
expect_exit 1 "is a directory, expected a file" "$tessera" volume info "$scratch/folder.nrrd"
expect_exit 1 "is a directory, expected a file" "$tessera" volume render sphere:8 --tf "$scratch/folder.json" \
  -o "$scratch/x.png" --size 8x8
expect_exit 1 "is a directory, expected a file" "$tessera" render "$scratch/folder.json" -o "$scratch/x.png"
expect_exit 2 "is actually a directory" "$tessera" patch "$scratch/folder.bpt" -o "$scratch/x.obj"
# Ranges read as people write them, not the largest double in 309 digits; sizes beyond an image state the limit.
expect_exit 2 "expected a number > 0, got 0" "$tessera" raster "$scratch/ball.ply" -o "$scratch/x.png" --repeat 0
[ "$(wc -c <"$scratch/stderr")" -lt 300 ] || { echo "--repeat 0: a long message"; cat "$scratch/stderr"; exit 1; }
expect_exit 2 "more than the 2147483648 (2^31) an image can hold" "$tessera" fractal mandelbrot -o "$scratch/m.png" \
  --size 65536x65536
# Input echoed in messages is escaped (no escape sequence reaches the terminal) and truncated (not a 10 MB line).
expect_exit 2 'got .1\\x1b\[2J' "$tessera" fractal mandelbrot -o "$scratch/m.png" --size $'1\e[2Jx5'
grep -q $'\e' "$scratch/stderr" && { echo "an escape byte reached stderr"; exit 1; }
printf 'v 0 0 0\nv 1 \033[2J 0\n' >"$scratch/esc.obj"
expect_exit 1 'got .\\x1b\[2J' "$tessera" mesh info "$scratch/esc.obj"
grep -q $'\e' "$scratch/stderr" && { echo "an escape byte from a mesh reached stderr"; exit 1; }
printf '<svg width="9" height="9"><rect width="5" height="5" fill="\033[2Jred"/></svg>' >"$scratch/esc.svg"
expect_exit 1 "unknown color '\\\\x1b\[2Jred'" "$tessera" canvas render "$scratch/esc.svg" -o "$scratch/x.png"
# A color option quotes its value escaped too (the terminal must not receive the escape sequence).
expect_exit 2 "got 're\\\\x1b\[2Jd'" "$tessera" raster "$scratch/ball.ply" -o "$scratch/x.png" --background "$(printf 're\033[2Jd')"
grep -q $'\e' "$scratch/stderr" && { echo "an escape byte from an SVG reached stderr"; exit 1; }
head -c 10000000 /dev/zero | tr '\0' '7' >"$scratch/long.csv"
expect_exit 1 "bytes)" "$tessera" color convert --from rgb --to hsv <"$scratch/long.csv"
[ "$(wc -c <"$scratch/stderr")" -lt 1000 ] || { echo "a long line echoed in full"; exit 1; }
# Duplicate keys in a scene are refused, naming the key and where it is.
printf '{"objects": [{"type": "sphere", "radius": 1, "radius": 2}]}' >"$scratch/dup.json"
expect_exit 1 "objects\[0\]: duplicate key 'radius'" "$tessera" render "$scratch/dup.json" -o "$scratch/x.png"
echo "cli basics: ok"
