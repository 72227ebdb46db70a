#!/bin/sh
# What automatic stereo costs a modern renderer: each of glmark2's scenes
# (Debian's glmark2-x11, GLX) run mono without the layer, then under
# `glstereo-run` without --auto, then under `glstereo-run --auto` (two
# rendered eyes) and `--auto=depth` (one render, eyes from its depth),
# ROUNDS times alternated, on a private Xvfb; prints each scene's frame
# rates and the ratios of the medians (layer / mono, --auto / mono,
# --auto=depth / mono, --auto=depth / --auto). Then the same
# for a few scenes of glmark2-es2 (EGL, OpenGL ES; GLMARK2_ES_SCENES), and
# glxgears under --auto against its own -stereo mode (display lists).
#
#   sh benches/auto_glmark2.sh [ROUNDS [SECONDS [SIZE]]]
#       (default 3 rounds, 4 s a scene, 800x600; the Xvfb screen fits SIZE)
#
# Uses the release build (cargo build --release -p glstereo-preload).
# Run it on a quiet machine: llvmpipe takes both cores.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
ROUNDS=${1:-3}
SECONDS_PER=${2:-4}
SIZE=${3:-800x600}
RUN="$ROOT/target/release/glstereo-run"
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
command -v glmark2 >/dev/null || { echo "install glmark2-x11" >&2; exit 1; }
command -v glxgears >/dev/null || { echo "install mesa-utils" >&2; exit 1; }

SW=$(( ${SIZE%x*} + 64 )); SH=$(( ${SIZE#*x} + 64 ))
# A display no other server holds (a run just ended may still hold :91).
N=91
while [ -e "/tmp/.X$N-lock" ]; do N=$((N + 1)); done
Xvfb :$N -screen 0 ${SW}x${SH}x24 -nolisten tcp >/dev/null 2>&1 &
XVFB=$!
trap 'kill $XVFB 2>/dev/null' EXIT INT TERM
sleep 2
export DISPLAY=:$N

SCENES="build:use-vbo=true texture:texture-filter=linear shading:shading=phong
bump:bump-render=high-poly effect2d:kernel=0,1,0;1,-4,1;0,1,0;
pulsar:quads=5:texture=false:light=false
desktop:windows=4:effect=blur:blur-radius=5:passes=1:separable=true
desktop:windows=4:effect=shadow
buffer:update-fraction=0.5:update-dispersion=0.9:columns=200:update-method=map:interleave=false
ideas:speed=duration jellyfish terrain shadow refract
conditionals:vertex-steps=0:fragment-steps=5 function:fragment-steps=5:fragment-complexity=low
loop:vertex-steps=5:fragment-steps=5:fragment-loop=false"

fps() {
    "$@" 2>/dev/null | sed -n 's/.*FPS: \([0-9]*\).*/\1/p' | tail -n 1
}

median() {
    tr ' ' '\n' | grep -v '^$' | sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'
}

ratio() {
    awk -v a="$1" -v m="$2" 'BEGIN {printf "%.2f", (m > 0) ? a / m : 0}'
}

# table EXE SCENES: mono, the layer without --auto, --auto.
table() {
    exe=$1
    printf '%-28s %-16s %-16s %-16s %-16s %s\n' "$exe scene" "mono fps" "layer fps" \
        "--auto fps" "depth fps" "layer/mono auto/mono depth/mono depth/auto"
    for scene in $2; do
        mono=""
        layer=""
        auto=""
        depth=""
        i=0
        while [ "$i" -lt "$ROUNDS" ]; do
            mono="$mono $(fps "$exe" -s "$SIZE" -b "$scene:duration=$SECONDS_PER")"
            layer="$layer $(fps "$RUN" "$exe" -s "$SIZE" -b "$scene:duration=$SECONDS_PER")"
            auto="$auto $(fps "$RUN" --auto -m side-by-side-half "$exe" -s "$SIZE" -b "$scene:duration=$SECONDS_PER")"
            depth="$depth $(fps "$RUN" --auto=depth -m side-by-side-half "$exe" -s "$SIZE" -b "$scene:duration=$SECONDS_PER")"
            i=$((i + 1))
        done
        m=$(echo "$mono" | median)
        l=$(echo "$layer" | median)
        a=$(echo "$auto" | median)
        d=$(echo "$depth" | median)
        printf '%-28s %-16s %-16s %-16s %-16s %s %s %s %s\n' "$(echo "$scene" | cut -c1-28)" \
            "$mono" "$layer" "$auto" "$depth" "$(ratio "$l" "$m")" "$(ratio "$a" "$m")" \
            "$(ratio "$d" "$m")" "$(ratio "$d" "$a")"
    done
}

table glmark2 "$SCENES"
if command -v glmark2-es2 >/dev/null; then
    table glmark2-es2 "${GLMARK2_ES_SCENES:-build:use-vbo=true shading:shading=phong texture:texture-filter=linear refract}"
else
    echo "glmark2-es2 not installed (glmark2-es2-x11): its EGL scenes skipped"
fi

# glxgears: --auto (display lists of geometry only: the fast path) against
# its own quad-buffer stereo under the layer.
gears() {
    timeout $((SECONDS_PER * 2 + 3)) "$@" 2>/dev/null | sed -n 's/.*= \([0-9.]*\) FPS.*/\1/p' | tail -n 1
}
auto=""
stereo=""
i=0
while [ "$i" -lt "$ROUNDS" ]; do
    auto="$auto $(gears "$RUN" --auto -m side-by-side-half glxgears -geometry 300x300)"
    stereo="$stereo $(gears "$RUN" -m side-by-side-half glxgears -stereo -geometry 300x300)"
    i=$((i + 1))
done
a=$(echo "$auto" | median)
s=$(echo "$stereo" | median)
printf '%-28s %-18s %-18s %s\n' "glxgears --auto / -stereo" "$stereo" "$auto" \
    "$(awk -v a="$a" -v s="$s" 'BEGIN {printf "%.2f", (s > 0) ? a / s : 0}')"
