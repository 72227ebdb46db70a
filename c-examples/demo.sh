#!/bin/sh
# Runs every C example headless and says where the images are.
set -eu
BUILD=${BUILD:-$(dirname "$0")/build}
OUT=${OUT:-out}
mkdir -p "$OUT"
echo "== projection (math only)"
"$BUILD/projection"
