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
"$BUILD/redblue$SUFFIX" --out "$OUT/redblue"

echo "== autostereo on $GLSTEREO_BACKEND (a mono program, automatic stereo)"
"$BUILD/autostereo$SUFFIX" --out "$OUT/autostereo" --frames 5

echo
echo "images are in $OUT/"
