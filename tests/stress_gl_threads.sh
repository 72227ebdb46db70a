#!/bin/sh
# Stress loop of the multi-threaded GL tests: surfaces on several threads
# composing on llvmpipe at once (EGL and OSMesa). Runs, RUNS times each,
# under CPU load (LOAD busy loops at the script's own priority: start the
# script with `nice -n 10` on a shared machine):
#   - tests/output_gl.rs and tests/output_gl_osmesa.rs as `cargo test` runs
#     them (tests in parallel threads, each on its own surface);
#   - the ignored stress test of tests/gl_threads.rs (GLSTEREO_STRESS_THREADS
#     threads of GLSTEREO_STRESS_ROUNDS surfaces each).
# With COLD=1 (the default) Mesa's shader cache is off, so every run compiles
# every shader again (with a warm cache nothing is compiled twice, and code
# that runs only while compiling is never exercised twice).
#
#   tests/stress_gl_threads.sh [RUNS [LOAD]]     (default 100 runs, load 2)
#
# ONLY=NAME runs one of the three loops. Core files are kept (the script
# raises `ulimit -c` where it may and the kernel's core_pattern is a plain
# file name).
#
# Prints each failed run (the signal that killed it, or its panic; its
# output is kept in the scratch directory, a core file beside it when
# `ulimit -c` allows) and, for each binary, how many runs passed and how many
# were killed by a signal (a crash). Exit 0 when every run passed.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
RUNS=${1:-100}
LOAD=${2:-2}
COLD=${COLD:-1}
cd "$ROOT" || exit 1
ulimit -c unlimited 2>/dev/null || true
build() {
    cargo test --no-run --message-format=json --test "$1" 2>/dev/null |
        sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1
}
OUTPUT_GL=$(build output_gl)
OUTPUT_GL_OSMESA=$(build output_gl_osmesa)
GL_THREADS=$(build gl_threads)
[ -x "$OUTPUT_GL" ] && [ -x "$OUTPUT_GL_OSMESA" ] && [ -x "$GL_THREADS" ] || {
    echo "building the tests failed" >&2
    exit 1
}
ONLY=${ONLY:-}
DIR="$ROOT/target/stress-gl-threads"
mkdir -p "$DIR"
[ "$COLD" = 1 ] && export MESA_SHADER_CACHE_DISABLE=true
LOADERS=
i=0
while [ "$i" -lt "$LOAD" ]; do
    sh -c 'while :; do :; done' &
    LOADERS="$LOADERS $!"
    i=$((i + 1))
done
trap '[ -n "$LOADERS" ] && kill $LOADERS 2>/dev/null' EXIT INT TERM

# loop NAME COMMAND...: runs COMMAND RUNS times; prints its tally.
loop() {
    name=$1
    shift
    ok=0
    crashed=0
    n=1
    while [ "$n" -le "$RUNS" ]; do
        out="$DIR/$name-$n.out"
        (cd "$DIR" && exec "$@") >"$out" 2>&1
        rc=$?
        if [ "$rc" -eq 0 ]; then
            ok=$((ok + 1))
            rm -f "$out"
        elif [ "$rc" -gt 128 ]; then
            crashed=$((crashed + 1))
            echo "$name run $n crashed: killed by signal $((rc - 128)) ($(kill -l $((rc - 128))))"
            [ -f "$DIR/core" ] && mv "$DIR/core" "$DIR/$name-$n.core"
        else
            echo "$name run $n failed (exit $rc): $(grep -m 2 -E 'panicked|overflow' "$out" | tr '\n' ' ')"
        fi
        n=$((n + 1))
    done
    echo "$name: $ok of $RUNS runs passed, $crashed crashed (load $LOAD, shader cache $([ "$COLD" = 1 ] && echo off || echo on))"
    [ "$ok" -eq "$RUNS" ]
}

# ONLY=NAME runs one binary's loop (output_gl, output_gl_osmesa, gl_threads).
want() { [ -z "$ONLY" ] || [ "$ONLY" = "$1" ]; }
status=0
want output_gl && { loop output_gl "$OUTPUT_GL" || status=1; }
want output_gl_osmesa && { loop output_gl_osmesa "$OUTPUT_GL_OSMESA" || status=1; }
want gl_threads && { loop gl_threads "$GL_THREADS" --ignored stress_surfaces_on_threads_compose_at_once || status=1; }
exit $status
