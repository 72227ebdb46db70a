#!/bin/sh
# Issue 39 item 5 on glmark2: does `--auto=depth` (one render, eyes moved
# by depth) give each scene the parallax of `--auto` (two rendered eyes)?
# For each scene: the convergence `--auto` finds for it (-v) is fixed for
# both modes (--convergence C), each mode runs the scene SECONDS with
# every frame captured (--capture), and examples/eye_parallax measures
# the captured pairs at 10 %, 20 %, ... 90 % of each run (block
# matching, 16x16 blocks; glmark2 animates by time, so a frame at the
# same fraction of two runs of a scene is at about the same moment of
# it, though the modes run at different frame rates);
# printed per mode: the medians over those frames of the per-frame 10 %,
# 50 % and 90 % quantiles of the blocks' horizontal shift (pixels; right
# eye minus left, positive behind the screen) and of the blocks matched.
# The moments match only roughly, so a scene whose camera moves fast
# (ideas) differs by that too.
#
#   sh benches/auto_depth_parallax.sh [SECONDS [SIZE]]
#       (default 4 s a scene, 800x600)
#
# Uses the release builds: cargo build --release -p glstereo-preload
# && cargo build --release --example eye_parallax.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_PER=${1:-4}
SIZE=${2:-800x600}
RUN="$ROOT/target/release/glstereo-run"
MEASURE="$ROOT/target/release/examples/eye_parallax"
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
[ -x "$MEASURE" ] || { echo "build first: cargo build --release --example eye_parallax" >&2; exit 1; }
command -v glmark2 >/dev/null || { echo "install glmark2-x11" >&2; exit 1; }

SW=$(( ${SIZE%x*} + 64 )); SH=$(( ${SIZE#*x} + 64 ))
N=93
while [ -e "/tmp/.X$N-lock" ]; do N=$((N + 1)); done
Xvfb :$N -screen 0 ${SW}x${SH}x24 -nolisten tcp >/dev/null 2>&1 &
XVFB=$!
TMP=$(mktemp -d)
trap 'kill $XVFB 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
sleep 2
export DISPLAY=:$N

SCENES="build:use-vbo=true shading:shading=phong bump:bump-render=high-poly
jellyfish shadow refract terrain desktop:windows=4:effect=shadow ideas:speed=duration"

median() {
    tr ' ' '\n' | grep -v '^$' | sort -n | awk '{a[NR] = $1} END {if (NR == 0) print "-"; else print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'
}

# measure DIR: "p10 p50 p90 matched" medians over the frames measured.
measure() {
    P10=""; P50=""; P90=""; M=""
    n=$(ls "$1"/left-*.png 2>/dev/null | wc -l)
    for l in $(ls "$1"/left-*.png 2>/dev/null | awk -v n="$n" '
        BEGIN {for (k = 1; k <= 9; k++) want[int(n * k / 10) + 1] = 1} want[NR]'); do
        r=$(echo "$l" | sed 's/left-/right-/')
        line=$("$MEASURE" "$l" "$r" 2>/dev/null | head -n 1)
        set -- $line
        # "N of T blocks matched, K off their rows; shift p10 A median B p90 C"
        [ "$1" -gt 0 ] 2>/dev/null || continue
        M="$M $1"
        P10="$P10 $(echo "$line" | sed 's/.*p10 \([-0-9]*\).*/\1/')"
        P50="$P50 $(echo "$line" | sed 's/.*median \([-0-9]*\).*/\1/')"
        P90="$P90 $(echo "$line" | sed 's/.*p90 \([-0-9]*\).*/\1/')"
    done
    echo "$(echo $P10 | median) $(echo $P50 | median) $(echo $P90 | median) $(echo $M | median)"
}

echo "| scene | convergence | --auto p10 / median / p90 (blocks) | --auto=depth p10 / median / p90 (blocks) | differences |"
echo "|---|---|---|---|---|"
for scene in $SCENES; do
    name=${scene%%:*}
    C=$("$RUN" -v --auto glmark2 -s "$SIZE" -b "$scene:duration=1" 2>&1 \
        | sed -n 's/.*automatic convergence at \([0-9.]*\).*/\1/p' | tail -n 1)
    [ -n "$C" ] || { echo "| $name | (no convergence found) | | | |"; continue; }
    run() {
        rm -rf "$TMP/cap"
        "$RUN" "$1" --convergence "$C" -c "$TMP/cap" \
            glmark2 -s "$SIZE" -b "$scene:duration=$SECONDS_PER" >/dev/null 2>&1
        measure "$TMP/cap"
    }
    GEOMETRY=$(run --auto)
    DEPTH=$(run --auto=depth)
    set -- $GEOMETRY
    A="$1 / $2 / $3 ($4)"; a10=$1; a50=$2; a90=$3
    set -- $DEPTH
    D="$1 / $2 / $3 ($4)"
    diff=$(awk -v a="$a10 $a50 $a90" -v d="$1 $2 $3" 'BEGIN {split(a, x, " "); split(d, y, " "); printf "%+d %+d %+d", y[1] - x[1], y[2] - x[2], y[3] - x[3]}')
    echo "| $name | $C | $A | $D | $diff |"
done
