#!/bin/sh
# Frame-loop cost of the LD_PRELOAD layer (benches/glx_frame_loop.c) on a
# private Xvfb: mono without the layer, mono under glstereo-run (must cost
# the same), stereo under glstereo-run (anaglyph-red-cyan, the default, and
# side-by-side-half), and stereo with --capture. Then, for the light scene
# at WIDTH x HEIGHT and 400x300 and the heavy scene at WIDTH x HEIGHT,
# ROUNDS rounds that alternate mono without the layer and stereo under it,
# each round printing stereo/mono of its medians.
#
#   benches/glx_frame_loop.sh [WIDTH HEIGHT [FRAMES [ROUNDS]]]   (default 1280 1024 200 3)
#
# Uses the release build: run `cargo build --release -p glstereo-preload`
# first. BASE_RUN=/path/to/another/glstereo-run adds that build's stereo
# frames to every round (an old/new comparison in one session). Timings
# depend on the machine and its load; compare runs made together.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
W=${1:-1280}
H=${2:-1024}
N=${3:-200}
ROUNDS=${4:-3}
RUN="$ROOT/target/release/glstereo-run"
BASE=${BASE_RUN:-}
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
TMP=$(mktemp -d)
XVFB=
trap '[ -n "$XVFB" ] && kill "$XVFB" 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/glx_frame_loop.c" -o "$TMP/loop" -lGL -lX11
Xvfb -displayfd 3 -screen 0 $((W + 64))x$((H + 64))x24 -nolisten tcp 3>"$TMP/display" >/dev/null 2>&1 &
XVFB=$!
while [ ! -s "$TMP/display" ]; do sleep 0.05; done
export DISPLAY=":$(cat "$TMP/display")"
echo "without the layer:    $("$TMP/loop" mono "$W" "$H" "$N")"
echo "under glstereo-run:   $("$RUN" "$TMP/loop" mono "$W" "$H" "$N")"
echo "                      $("$RUN" "$TMP/loop" stereo "$W" "$H" "$N")  (anaglyph-red-cyan)"
echo "                      $("$RUN" -m side-by-side-half "$TMP/loop" stereo "$W" "$H" "$N")  (side-by-side-half)"
echo "with --capture:       $("$RUN" --capture "$TMP/frames" "$TMP/loop" stereo "$W" "$H" "$N")"
echo "captured $(ls "$TMP/frames" | wc -l) files"

# The median of one run's output line.
median() { sed 's/.*median \([0-9.]*\) ms.*/\1/'; }

# rounds SCENE WIDTH HEIGHT FRAMES: alternated mono / stereo (/ base stereo).
rounds() {
    i=1
    while [ "$i" -le "$ROUNDS" ]; do
        # The base build runs first in even rounds, so that neither build
        # always follows the mono program.
        if [ -n "$BASE" ] && [ $((i % 2)) -eq 0 ]; then
            b=$("$BASE" "$TMP/loop" stereo "$2" "$3" "$4" "$1" | median)
        fi
        m=$("$TMP/loop" mono "$2" "$3" "$4" "$1" | median)
        s=$("$RUN" "$TMP/loop" stereo "$2" "$3" "$4" "$1" | median)
        if [ -n "$BASE" ] && [ $((i % 2)) -eq 1 ]; then
            b=$("$BASE" "$TMP/loop" stereo "$2" "$3" "$4" "$1" | median)
        fi
        line="$1 $2x$3 round $i: mono $m ms, stereo $s ms, stereo/mono $(echo "$s $m" | awk '{printf "%.2f", $1 / $2}')"
        if [ -n "$BASE" ]; then
            line="$line; base stereo $b ms, $(echo "$b $m" | awk '{printf "%.2f", $1 / $2}')"
        fi
        echo "$line"
        i=$((i + 1))
    done
}
rounds light "$W" "$H" "$N"
rounds light 400 300 $((N * 4))
rounds heavy "$W" "$H" $((N / 20 > 5 ? N / 20 : 5))
