#!/bin/sh
# Automatic stereo's cost (issue 23 item 7), with benches/glx_frame_loop.c
# on a private Xvfb. For the light, heavy, heavy3d (perspective), lit3d
# (heavy3d under fixed-function lighting) and shader3d
# (perspective, a GLSL program) scenes at 400x300 and
# 1280x1024, ROUNDS rounds each alternate, in an order that turns each
# round:
#
#   auto   glstereo-run --auto   glx_frame_loop mono    (a mono program; the
#                                                        layer draws both eyes)
#   own    glstereo-run          glx_frame_loop stereo  (the same scene, both
#                                                        eyes drawn by the program)
#   plain                        glx_frame_loop mono    (no layer)
#   layer  glstereo-run          glx_frame_loop mono    (no --auto: must cost
#                                                        what plain costs)
#   base   $BASE_RUN             glx_frame_loop mono    (if BASE_RUN is set: the
#                                                        same under an older build)
#
# each printing its median frame time (draw + glXSwapBuffers + glFinish),
# and per round the ratios auto/own, layer/plain (and layer/base). The
# last lines are the medians of those ratios over the rounds. Target:
# auto/own <= 1.1, layer/plain (and layer/base) 1.00 within the noise.
# Ratios of one run only; timings depend on the machine and its load.
#
#   benches/auto_frame_loop.sh [ROUNDS]                 (default 5)
#   SIZES=400x300 SCENES=heavy benches/auto_frame_loop.sh 3
#   BASE_RUN=/path/to/old/target/release/glstereo-run benches/auto_frame_loop.sh
#
# Uses the release build: run `cargo build --release -p glstereo-preload`
# first. The mode is the default (anaglyph-red-cyan) for every run under
# the layer; GLSTEREO_MODE changes it for all of them.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
ROUNDS=${1:-5}
SIZES=${SIZES:-"400x300 1280x1024"}
SCENES=${SCENES:-"light heavy heavy3d shader3d"}
RUN="$ROOT/target/release/glstereo-run"
BASE=${BASE_RUN:-}
[ -x "$RUN" ] || { echo "build first: cargo build --release -p glstereo-preload" >&2; exit 1; }
TMP=$(mktemp -d)
XVFB=
trap '[ -n "$XVFB" ] && kill "$XVFB" 2>/dev/null; rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/glx_frame_loop.c" -o "$TMP/loop" -lGL -lX11
Xvfb -displayfd 3 -screen 0 1344x1088x24 -nolisten tcp 3>"$TMP/display" >/dev/null 2>&1 &
XVFB=$!
while [ ! -s "$TMP/display" ]; do sleep 0.05; done
export DISPLAY=":$(cat "$TMP/display")"

# The median of one run's output line.
median() { sed 's/.*median \([0-9.]*\) ms.*/\1/'; }
ratio() { echo "$1 $2" | awk '{printf "%.2f", $1 / $2}'; }
# The median of the numbers on stdin.
middle() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

# run VARIANT SCENE W H FRAMES: that variant's median frame time. A run
# that prints nothing is made again, twice at most (on a loaded machine
# glx_frame_loop sometimes exits 1 before its first frame, with or
# without the layer).
run() {
    for _ in 1 2 3; do
        t=$(run_once "$@" || true)
        [ -n "$t" ] && break
    done
    echo "$t"
}
run_once() {
    case $1 in
    auto) "$RUN" --auto "$TMP/loop" mono "$3" "$4" "$5" "$2" ;;
    own) "$RUN" "$TMP/loop" stereo "$3" "$4" "$5" "$2" ;;
    plain) "$TMP/loop" mono "$3" "$4" "$5" "$2" ;;
    layer) "$RUN" "$TMP/loop" mono "$3" "$4" "$5" "$2" ;;
    base) "$BASE" "$TMP/loop" mono "$3" "$4" "$5" "$2" ;;
    esac | median
}

VARIANTS="auto own plain layer"
[ -n "$BASE" ] && VARIANTS="$VARIANTS base"
SUMMARY=$TMP/summary
for wh in $SIZES; do
    w=${wh%x*}
    h=${wh#*x}
    for scene in $SCENES; do
        case "$scene $wh" in
        "light 400x300") frames=400 ;;
        "light 1280x1024") frames=100 ;;
        "heavy 400x300" | "heavy3d 400x300" | "lit3d 400x300" | "shader3d 400x300") frames=20 ;;
        *) frames=10 ;;
        esac
        echo "# $scene $wh, $frames frames a run; $(uptime)"
        : >"$TMP/ratios"
        i=1
        while [ "$i" -le "$ROUNDS" ]; do
            # Rotate the order, so that no variant always follows another.
            order=$(echo $VARIANTS | awk -v r="$i" '{for (k = 0; k < NF; k++) printf "%s ", $((k + r - 1) % NF + 1)}')
            for v in $order; do
                eval "t_$v=\$(run $v $scene $w $h $frames)"
            done
            # shellcheck disable=SC2154
            line="round $i: auto $t_auto ms, own $t_own ms, auto/own $(ratio "$t_auto" "$t_own"); plain $t_plain ms, layer $t_layer ms, layer/plain $(ratio "$t_layer" "$t_plain")"
            r="$(ratio "$t_auto" "$t_own") $(ratio "$t_layer" "$t_plain")"
            if [ -n "$BASE" ]; then
                # shellcheck disable=SC2154
                line="$line; base $t_base ms, layer/base $(ratio "$t_layer" "$t_base")"
                r="$r $(ratio "$t_layer" "$t_base")"
            fi
            echo "$line"
            echo "$r" >>"$TMP/ratios"
            i=$((i + 1))
        done
        s="$scene $wh: auto/own $(cut -d' ' -f1 "$TMP/ratios" | middle), layer/plain $(cut -d' ' -f2 "$TMP/ratios" | middle)"
        [ -n "$BASE" ] && s="$s, layer/base $(cut -d' ' -f3 "$TMP/ratios" | middle)"
        echo "$s" >>"$SUMMARY"
    done
done
echo "# medians over $ROUNDS rounds"
cat "$SUMMARY"
