#!/bin/sh
# make test on a fresh Debian 12 machine: proves that the Makefile's package
# list (DEB_PACKAGES) is complete, which this machine, holding whatever
# earlier work installed, cannot.
#
#   sudo sh tests/fresh_machine.sh [COMMIT]     (as root; default HEAD)
#
# 1. mmdebstrap (Debian's package) builds a minimal Debian 12 root
#    (variant minbase: Essential packages and apt) from this machine's own
#    apt sources, with what a fresh development machine has besides: gcc,
#    make, git, CA certificates.
#    Its resolver and the extra certificate authorities this machine
#    trusts are copied in (the machine's network, as its apt sources).
# 2. The Rust toolchain this machine uses is mounted read-only into it
#    (rustup's active toolchain directory, put first on PATH); crates are
#    fetched afresh into the root's own CARGO_HOME.
# 3. A fresh clone of COMMIT goes to /root/glstereo inside, and `make test`
#    runs there as root with /proc, /sys and /dev mounted: it installs the
#    packages it needs itself, as on any fresh machine.
#
# The root lives under FRESH_DIR (default /var/tmp) and is removed at the
# end unless KEEP=1. The log is FRESH_DIR/glstereo-fresh-<pid>.log; the
# exit status is make test's. A chroot allows no user namespaces, so the
# tests' fallbacks for machines without them run here (tests/faults.rs).
# Time on this project's 2-core machine: README ("A fresh machine").
set -eu
ulimit -c unlimited 2>/dev/null || true

if [ "$(id -u)" != 0 ]; then
    echo "fresh_machine.sh: run me as root (mmdebstrap, chroot and mounts need it)" >&2
    exit 2
fi
command -v mmdebstrap >/dev/null || {
    echo "fresh_machine.sh: install mmdebstrap (apt-get install mmdebstrap)" >&2
    exit 2
}
top=$(cd "$(dirname "$0")/.." && pwd)
commit=$(git -C "$top" rev-parse --verify "${1:-HEAD}^{commit}")
toolchain=$(dirname "$(dirname "$(rustup which rustc)")")
base=${FRESH_DIR:-/var/tmp}
root="$base/glstereo-fresh-$$"
log="$base/glstereo-fresh-$$.log"
start=$(date +%s)

say() { printf 'fresh_machine.sh: %s\n' "$*" | tee -a "$log" >&2; }

mounted=""
cleanup() {
    for m in $mounted; do umount -l "$m" 2>/dev/null || true; done
    [ "${KEEP:-0}" = 1 ] && return
    # Never remove through a mount that is still there (/dev of the host).
    if grep -q " $root/" /proc/self/mounts; then
        say "something is still mounted under $root: left in place"
    else
        rm -rf --one-file-system "$root"
    fi
}
trap cleanup EXIT INT TERM

# The machine's own sources, one-line or deb822, as mmdebstrap reads them.
sources=$(mktemp)
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    case "$f" in
    *.sources) cat "$f"; echo ;;
    *) grep -E '^[[:space:]]*deb[[:space:]]' "$f" || true ;;
    esac
done >"$sources"

say "building a Debian 12 root in $root (log: $log)"
mmdebstrap --variant=minbase --include=ca-certificates,gcc,libc6-dev,make,git \
    bookworm "$root" - <"$sources" >>"$log" 2>&1
rm -f "$sources"
# This machine's network as it is: its resolver, and the certificate
# authorities it trusts besides Debian's (a proxy's, where https is
# intercepted; cargo fetches crates over https).
cp /etc/resolv.conf "$root/etc/resolv.conf"
if ls /usr/local/share/ca-certificates/*.crt >/dev/null 2>&1; then
    cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
    chroot "$root" update-ca-certificates >>"$log" 2>&1
fi

for d in proc sys dev; do
    mkdir -p "$root/$d"
done
mount -t proc proc "$root/proc" && mounted="$root/proc $mounted"
mount --rbind /sys "$root/sys" && mounted="$root/sys $mounted"
mount --rbind /dev "$root/dev" && mounted="$root/dev $mounted"
mkdir -p "$root/opt/rust"
mount --bind "$toolchain" "$root/opt/rust" && mounted="$root/opt/rust $mounted"
mount -o remount,bind,ro "$root/opt/rust"

git clone -q --no-hardlinks "$top" "$root/root/glstereo"
touch "$root/.started"
git -C "$root/root/glstereo" checkout -q "$commit"
say "make test at $(git -C "$top" log -1 --format='%h %s' "$commit" | cut -c1-72)"

status=0
chroot "$root" /usr/bin/env -i HOME=/root USER=root LANG=C.UTF-8 TERM=dumb \
    PATH=/opt/rust/bin:/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    CARGO_HOME=/root/.cargo \
    /bin/sh -c 'cd /root/glstereo && make test' >>"$log" 2>&1 || status=$?

# A crash's core files (core_pattern "core": in the crashed test's
# directory) are kept beside the log for gdb.
if [ "$status" != 0 ]; then
    # "core" or "core.PID" (core_uses_pid): not core_stereo-*, core.rs.html.
    find "$root/root/glstereo" -type f \( -name core -o -name 'core.[0-9]*' \) \
        -newer "$root/.started" 2>/dev/null |
        while read -r core; do
            cp "$core" "$base/glstereo-fresh-$$-$(basename "$(dirname "$core")")-$(basename "$core")"
            say "kept $core"
        done
fi
took=$(( $(date +%s) - start ))
say "make test exited $status after $((took / 60)) min $((took % 60)) s (log: $log)"
grep -E '^test result:|FAILED|panicked' "$log" | tail -40 >&2 || true
exit "$status"
