#!/bin/sh
# Runs every C example headless and says where the images are.
# GLSTEREO_BACKEND=osmesa runs the OSMesa builds; anything else uses EGL.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${BUILD:-$HERE/build}
OUT=${OUT:-out}
case "${GLSTEREO_BACKEND:-egl}" in
  osmesa) SUFFIX=-osmesa ;;
  *) SUFFIX=""; GLSTEREO_BACKEND=egl ;;
esac
export GLSTEREO_BACKEND
mkdir -p "$OUT"

echo "== projection (math only)"
"$BUILD/projection"

echo "== redblue on $GLSTEREO_BACKEND"
"$BUILD/redblue$SUFFIX" --out "$OUT/redblue" \
  --modes anaglyph-red-cyan,anaglyph-red-cyan-dubois,side-by-side,top-bottom,rows

echo "== starbase (HP Starbase gescape(STEREO), sync-doubled) on $GLSTEREO_BACKEND"
"$BUILD/starbase$SUFFIX" --out "$OUT/starbase"

echo "== irisgl (SGI IRIS GL STR_RECT, then square-pixel stereo) on $GLSTEREO_BACKEND"
"$BUILD/irisgl$SUFFIX" --out "$OUT/irisgl/str-rect"
"$BUILD/irisgl$SUFFIX" --square-pixel --out "$OUT/irisgl/square-pixel"

echo "== oglplane on $GLSTEREO_BACKEND: one turn of the airplane, parallax measured each frame,"
echo "   the last frame also as stereo photos (oglplane.mpo, oglplane.jps)"
"$BUILD/oglplane$SUFFIX" --frames 60 --angle -54 --out "$OUT/oglplane"

echo "== autostereo on $GLSTEREO_BACKEND (a mono program, automatic stereo)"
"$BUILD/autostereo$SUFFIX" --out "$OUT/autostereo" --frames 5

echo "== xinerama (seed 001 passive stereo: one double-width mono frame) on $GLSTEREO_BACKEND"
"$BUILD/xinerama$SUFFIX" --out "$OUT/xinerama" --size 320x240 --modes side-by-side

echo
echo "images are in $OUT/"
