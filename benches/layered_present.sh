#!/bin/sh
# What presenting through another GL layer's glXSwapBuffers costs: the
# stereo frame loop of benches/glx_frame_loop.c under glstereo-run alone
# (on llvmpipe the composite goes into the window with MIT-SHM, no swap)
# and with a layer below glstereo (tests/clients/forwarder.c, which only
# forwards; then every frame is composed with GL and goes through that
# layer's glXSwapBuffers), in ROUNDS alternated rounds, each printing
# layered/alone of the medians; and the same with MangoHud below when it
# is installed (its HUD drawn every frame: its own cost is in that number).
#
#   benches/layered_present.sh [WIDTH HEIGHT [FRAMES [ROUNDS [MODE]]]]
#       (default 1280 1024 200 3 anaglyph-red-cyan)
#
# Uses the release build: run `cargo build --release -p glstereo-preload`
# first. Timings depend on the machine and its load; compare ratios.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
W=${1:-1280}
H=${2:-1024}
N=${3:-200}
ROUNDS=${4:-3}
MODE=${5:-anaglyph-red-cyan}
RUN="$ROOT/target/release/glstereo-run"
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
TMP=$(mktemp -d)
XVFB=
trap '[ -n "$XVFB" ] && kill "$XVFB" 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/glx_frame_loop.c" -o "$TMP/loop" -lGL -lX11
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror -fPIC -shared -Wl,-Bsymbolic-functions \
    "$ROOT/tests/clients/forwarder.c" -o "$TMP/forwarder.so" -Wl,--no-as-needed -lGL -lX11
MANGOHUD=/usr/lib/x86_64-linux-gnu/mangohud/libMangoHud.so
Xvfb -displayfd 3 -screen 0 $((W + 64))x$((H + 64))x24 -nolisten tcp 3>"$TMP/display" >/dev/null 2>&1 &
XVFB=$!
while [ ! -s "$TMP/display" ]; do sleep 0.05; done
export DISPLAY=":$(cat "$TMP/display")"

median() { grep 'median' | tail -n 1 | sed 's/.*median \([0-9.]*\) ms.*/\1/'; }
alone() { "$RUN" -m "$MODE" "$TMP/loop" stereo "$W" "$H" "$N" | median; }
# The layer goes after glstereo in LD_PRELOAD (glstereo-run puts itself first).
below() { LD_PRELOAD="$1" "$RUN" -m "$MODE" "$TMP/loop" stereo "$W" "$H" "$N" | median; }
ratio() { echo "$1 $2" | awk '{printf "%.2f", $1 / $2}'; }

echo "mode $MODE, ${W}x${H}, $N frames a run; $(uptime | sed 's/.*load/load/')"
i=1
while [ "$i" -le "$ROUNDS" ]; do
    if [ $((i % 2)) -eq 1 ]; then
        a=$(alone); f=$(below "$TMP/forwarder.so")
    else
        f=$(below "$TMP/forwarder.so"); a=$(alone)
    fi
    line="round $i: alone $a ms, forwarding layer below $f ms, below/alone $(ratio "$f" "$a")"
    if [ -f "$MANGOHUD" ]; then
        m=$(MANGOHUD=1 below "$MANGOHUD")
        line="$line; MangoHud below $m ms, $(ratio "$m" "$a")"
    fi
    echo "$line"
    i=$((i + 1))
done
