#!/bin/sh
# Per-eye mechanisms for automatic stereo on llvmpipe (benches/auto_mechanisms.c,
# issue 23): for the light and heavy scenes at 400x300 and 1280x1024, N = 1, 10,
# 100 and 1000 draws per frame, every variant alternated in each of ROUNDS
# rounds (a few frames each), on an EGL surfaceless context with
# LP_NUM_THREADS rasterizer threads (default 2). Prints the load before each
# block, and per variant the median over rounds of its ratio to the first
# variant in the same round; compare numbers of one run only.
#
#   benches/auto_mechanisms.sh [ROUNDS]    (default 6)
#   VARIANTS="a d dff" SIZES=400x300 SCENES=light NS="10 100" benches/auto_mechanisms.sh
#   (a subset; a first, the reference of the ratios)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
ROUNDS=${1:-6}
# Variants to run (all by default); the first is the reference of the ratios.
VARIANTS=${VARIANTS:-}
# Sizes (WxH), scenes and draw counts to run.
SIZES=${SIZES:-"400x300 1280x1024"}
SCENES=${SCENES:-"light heavy"}
NS=${NS:-"1 10 100 1000"}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/auto_mechanisms.c" -o "$TMP/am" -lEGL -lOpenGL -lm
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
"$TMP/am" probe | head -1
"$TMP/am" verify 400 300
for wh in $SIZES; do
    size="${wh%x*} ${wh#*x}"
    for scene in $SCENES; do
        for n in $NS; do
            case "$scene $wh" in
            "light 400x300") frames=10 ;;
            "light 1280x1024") frames=4 ;;
            "heavy 400x300") frames=2 ;;
            *) frames=1 ;;
            esac
            echo "# $(uptime)"
            # shellcheck disable=SC2086
            "$TMP/am" run $size "$scene" "$n" "$frames" "$ROUNDS" $VARIANTS
        done
    done
done
