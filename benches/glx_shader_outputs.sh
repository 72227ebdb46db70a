#!/bin/sh
# What the duplicated fragment output of a stereo context costs
# (benches/glx_shader_outputs.c, under glstereo-run on a private Xvfb):
# link time, one-pass draws against gl_FragColor and against a pass per
# eye, and draws into the program's own framebuffer object.
#
#   benches/glx_shader_outputs.sh [WIDTH HEIGHT [ROUNDS]]    (default 1280 1024 30)
#
# Uses the release build: run `cargo build --release -p glstereo-preload`
# first. Timings depend on the machine and its load; the ratios come from
# one run, both sides alternated.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
W=${1:-1280}
H=${2:-1024}
N=${3:-30}
RUN="$ROOT/target/release/glstereo-run"
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
TMP=$(mktemp -d)
XVFB=
trap '[ -n "$XVFB" ] && kill "$XVFB" 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/glx_shader_outputs.c" -o "$TMP/bench" -lGL -lX11
Xvfb -displayfd 3 -screen 0 $((2 * W + 64))x$((H + 64))x24 -nolisten tcp 3>"$TMP/display" >/dev/null 2>&1 &
XVFB=$!
while [ ! -s "$TMP/display" ]; do sleep 0.05; done
export DISPLAY=":$(cat "$TMP/display")"
"$RUN" "$TMP/bench" "$W" "$H" "$N"
