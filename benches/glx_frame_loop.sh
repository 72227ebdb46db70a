#!/bin/sh
# Frame-loop cost of the LD_PRELOAD layer (benches/glx_frame_loop.c) on a
# private Xvfb: mono without the layer, mono under glstereo-run (must cost
# the same), stereo under glstereo-run (anaglyph-red-cyan, the default, and
# side-by-side-half), and stereo with --capture.
#
#   benches/glx_frame_loop.sh [WIDTH HEIGHT [FRAMES]]      (default 1280 1024 200)
#
# Uses the release build: run `cargo build --release -p glstereo-preload`
# first. Timings depend on the machine and its load; compare runs made
# together.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
W=${1:-1280}
H=${2:-1024}
N=${3:-200}
RUN="$ROOT/target/release/glstereo-run"
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
