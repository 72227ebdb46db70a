#!/bin/sh
# Per-eye mechanisms for automatic stereo on llvmpipe (benches/auto_mechanisms.c,
# issue 23): for the light and heavy scenes at 400x300 and 1280x1024, N = 1, 10,
# 100 and 1000 draws per frame, every variant alternated in each of ROUNDS
# rounds, on an EGL surfaceless context with LP_NUM_THREADS rasterizer
# threads (default 2). Prints the load before each block; compare numbers of
# one run only.
#
#   benches/auto_mechanisms.sh [ROUNDS]    (default 3)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
ROUNDS=${1:-3}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT INT TERM
cc -O2 -std=c99 -Wall -Wextra -Wpedantic -Werror "$ROOT/benches/auto_mechanisms.c" -o "$TMP/am" -lEGL -lOpenGL -lm
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
"$TMP/am" probe | head -1
"$TMP/am" verify 400 300
for size in "400 300" "1280 1024"; do
    for scene in light heavy; do
        for n in 1 10 100 1000; do
            case "$scene $size" in
            "light 400 300") frames=40 ;;
            "light 1280 1024") frames=15 ;;
            "heavy 400 300") frames=5 ;;
            *) frames=2 ;;
            esac
            echo "# $(uptime)"
            # shellcheck disable=SC2086
            "$TMP/am" run $size "$scene" "$n" "$frames" "$ROUNDS"
        done
    done
done
