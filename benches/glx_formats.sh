#!/bin/sh
# Every output format's frame rate under glstereo-run, as a ratio to
# anaglyph-red-cyan's (the cheapest composite) measured in alternation:
# each round runs benches/glx_frame_loop.c in stereo under glstereo-run
# with anaglyph-red-cyan, then with the format, on a private Xvfb, and
# takes the ratio of their median frame times. Prints, per scene and size,
# one line per format: the medians over the rounds of both frame times and
# the range and median of the per-round ratios (fps of the format / fps of
# anaglyph-red-cyan: 1 = as fast, 0.5 = half the frame rate), then the
# same ratio of the program's CPU time a frame ("cpu": every thread of the
# program's process, llvmpipe's and the layer's composing included, the X
# server's not). On a machine shared with other jobs the frame times move
# with the load by more than the formats differ; the CPU-time ratio does
# not.
#
#   benches/glx_formats.sh [ROUNDS [FORMAT...]]       (default 3, every format)
#
# BASE_RUN=/path/to/another/glstereo-run measures that build's ratio too,
# in the same rounds (its own anaglyph-red-cyan and format runs next to
# this build's, the order alternating from round to round): a before /
# after table from one run.
#
# SCENES="light:1280x1024:200 light:400x300:800 heavy:1280x1024:6" (the
# default) chooses the scenes, sizes and frames per run. RUN=/path/to/
# glstereo-run measures another build (default: this tree's release build,
# `cargo build --release -p glstereo-preload` first). The environment
# reaches the layer: GLSTEREO_CROSSTALK=0.1, GLSTEREO_SATURATION=0.6,
# GALLIUM_DRIVER=softpipe, or LIBGL_ALWAYS_SOFTWARE=1
# MESA_LOADER_DRIVER_OVERRIDE=zink (Vulkan: lavapipe) measure those.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
ROUNDS=${1:-3}
[ $# -gt 0 ] && shift
RUN=${RUN:-"$ROOT/target/release/glstereo-run"}
BASE=${BASE_RUN:-}
SCENES=${SCENES:-"light:1280x1024:200 light:400x300:800 heavy:1280x1024:6"}
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
if [ $# -gt 0 ]; then
    FORMATS="$*"
else
    # Every mode glstereo-run lists (quad falls back to anaglyph-red-cyan).
    FORMATS=$("$RUN" --help | sed -n '/^Modes:/,/^$/p' | awk 'NR > 1 && NF { print $1 }')
fi
TMP=$(mktemp -d)
XVFB=
trap '[ -n "$XVFB" ] && kill "$XVFB" 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/glx_frame_loop.c" -o "$TMP/loop" -lGL -lX11
Xvfb -displayfd 3 -screen 0 1344x1088x24 -nolisten tcp 3>"$TMP/display" >/dev/null 2>&1 &
XVFB=$!
while [ ! -s "$TMP/display" ]; do sleep 0.05; done
export DISPLAY=":$(cat "$TMP/display")"

# The median frame time and the CPU time a frame (ms) of one run of BUILD
# in MODE: run BUILD MODE SCENE W H FRAMES ("failed failed" when it did
# not finish).
run() {
    out=$("$1" -m "$2" "$TMP/loop" stereo "$4" "$5" "$6" "$3" 2>&1) || true
    case $out in
    *median*cpu*) echo "$out" | sed -n 's/.*median \([0-9.]*\) ms.*cpu \([0-9.]*\) ms.*/\1 \2/p' ;;
    *) echo "failed: $2 (exit or signal, output: $out)" >&2; echo failed failed ;;
    esac
}
# ratio REF FMT: REF / FMT (the fps ratio), nan for a failed run.
ratio() { echo "$1 $2" | awk '$1 + 0 > 0 && $2 + 0 > 0 { printf "%.3f\n", $1 / $2; next } { print "nan" }'; }
# pair BUILD SCENE W H FRAMES FORMAT SUFFIX: one alternated pair of runs.
pair() {
    a=$(run "$1" anaglyph-red-cyan "$2" "$3" "$4" "$5")
    b=$(run "$1" "$6" "$2" "$3" "$4" "$5")
    echo "${a% *}" >>"$TMP/r$7"
    echo "${b% *}" >>"$TMP/f$7"
    ratio "${a% *}" "${b% *}" >>"$TMP/q$7"
    ratio "${a#* }" "${b#* }" >>"$TMP/c$7"
}
# stats FILE: the median and the range of the ratios in FILE.
stats() { printf '%8s %12s' "$(med <"$1")" "$(sort -g "$1" | sed -n '1p;$p' | paste -sd-)"; }
med() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

echo "# $(uptime)"
echo "# $RUN, $ROUNDS rounds, ${GALLIUM_DRIVER:-}${MESA_LOADER_DRIVER_OVERRIDE:-} ${GLSTEREO_CROSSTALK:+crosstalk $GLSTEREO_CROSSTALK} ${GLSTEREO_SATURATION:+saturation $GLSTEREO_SATURATION}"
for s in $SCENES; do
    scene=${s%%:*}
    rest=${s#*:}
    size=${rest%%:*}
    frames=${rest#*:}
    w=${size%x*}
    h=${size#*x}
    echo "## $scene $size, $frames frames a run"
    head=$(printf '%-30s %8s %8s %8s %12s %8s %12s' format "ref ms" "fmt ms" ratio range cpu range)
    [ -n "$BASE" ] && head="$head $(printf '%8s %12s %8s %12s' base range "base cpu" range)"
    echo "$head"
    for f in $FORMATS; do
        rm -f "$TMP"/[rfqc][nb]
        i=1
        while [ "$i" -le "$ROUNDS" ]; do
            # The base build goes first in even rounds.
            [ -n "$BASE" ] && [ $((i % 2)) -eq 0 ] && pair "$BASE" "$scene" "$w" "$h" "$frames" "$f" b
            pair "$RUN" "$scene" "$w" "$h" "$frames" "$f" n
            [ -n "$BASE" ] && [ $((i % 2)) -eq 1 ] && pair "$BASE" "$scene" "$w" "$h" "$frames" "$f" b
            i=$((i + 1))
        done
        line="$(printf '%-30s %8s %8s' "$f" "$(med <"$TMP/rn")" "$(med <"$TMP/fn")") $(stats "$TMP/qn") $(stats "$TMP/cn")"
        [ -n "$BASE" ] && line="$line $(stats "$TMP/qb") $(stats "$TMP/cb")"
        echo "$line"
    done
done
echo "# $(uptime)"
