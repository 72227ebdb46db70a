#!/bin/sh
# The Debian packages of `make deb` on a fresh Debian 12 machine, used as a
# person would use them (README, "Install"). Run it before a release:
#
#   make deb && sudo sh tests/deb_fresh_root.sh [DEB_DIR]   (default target/debian)
#
# 1. mmdebstrap (Debian's package) builds a minimal Debian 12 root (variant
#    minbase) from this machine's own apt sources, with its resolver and
#    the certificate authorities it trusts, as tests/fresh_machine.sh does;
#    /proc, /sys and /dev are mounted.
# 2. `apt-get install ./glstereo*.deb ./libglstereo*.deb` (this
#    architecture's packages of this version) must pull every dependency.
# 3. As a user (not root): glstereo-run is on PATH and finds the installed
#    preload library; `man glstereo-run` opens; a C program builds with
#    `cc prog.c $(pkg-config --cflags --libs glstereo)` and passes;
#    Debian's `glxgears -stereo` under `glstereo-run -m side-by-side-half
#    --capture DIR` on Xvfb writes a left and a right eye that differ.
#    What a user installs to do so (man-db, gcc, pkg-config, mesa-utils,
#    xvfb) is installed then, as apt-get would for that user.
# 4. Where DEB_DIR holds the i386 libglstereo-preload too (make deb
#    DEB_HOST_ARCH=i386): Debian's i386 glxgears under glstereo-run first
#    gets the one-line "install the i386 layer" message, then, with
#    libglstereo-preload:i386 installed, two different eyes as well.
# 5. `apt-get purge` of the packages leaves none of their files (dpkg -L,
#    read before) behind.
#
# The root lives under FRESH_DIR (default /var/tmp) and is removed at the
# end unless KEEP=1; the log is FRESH_DIR/glstereo-debroot-<pid>.log, and
# the left, right and composite PNGs compared are copied beside it. Exit
# status 0 when every check passed. Time: README ("Install").
set -eu

if [ "$(id -u)" != 0 ]; then
    echo "deb_fresh_root.sh: run me as root (mmdebstrap, chroot and mounts need it)" >&2
    exit 2
fi
command -v mmdebstrap >/dev/null || {
    echo "deb_fresh_root.sh: install mmdebstrap (apt-get install mmdebstrap)" >&2
    exit 2
}
top=$(cd "$(dirname "$0")/.." && pwd)
debs=$(cd "${1:-$top/target/debian}" && pwd)
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$top/Cargo.toml" | head -n 1)
arch=$(dpkg --print-architecture)
pkgs="glstereo libglstereo0 libglstereo-dev libglstereo-preload"
for p in $pkgs; do
    [ -f "$debs/${p}_${version}_$arch.deb" ] || {
        echo "deb_fresh_root.sh: no $debs/${p}_${version}_$arch.deb: run make deb first" >&2
        exit 2
    }
done
i386=""
if [ "$arch" = amd64 ] && [ -f "$debs/libglstereo-preload_${version}_i386.deb" ]; then
    i386=yes
fi
base=${FRESH_DIR:-/var/tmp}
root="$base/glstereo-debroot-$$"
log="$base/glstereo-debroot-$$.log"
start=$(date +%s)

say() { printf 'deb_fresh_root.sh: %s\n' "$*" | tee -a "$log" >&2; }

mounted=""
cleanup() {
    for m in $mounted; do umount -l "$m" 2>/dev/null || true; done
    [ "${KEEP:-0}" = 1 ] && return
    if grep -q " $root/" /proc/self/mounts; then
        say "something is still mounted under $root: left in place"
    else
        rm -rf --one-file-system "$root"
    fi
}
trap cleanup EXIT INT TERM

sources=$(mktemp)
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    case "$f" in
    *.sources) cat "$f"; echo ;;
    *) grep -E '^[[:space:]]*deb[[:space:]]' "$f" || true ;;
    esac
done >"$sources"

say "building a Debian 12 root in $root (log: $log)"
mmdebstrap --variant=minbase --include=ca-certificates bookworm "$root" - <"$sources" >>"$log" 2>&1
rm -f "$sources"
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

# What a person downloads: the packages; and the C program of item 3.
mkdir -p "$root/tmp/debs" "$root/tmp/prog"
for p in $pkgs; do
    cp "$debs/${p}_${version}_$arch.deb" "$root/tmp/debs/"
done
[ -z "$i386" ] || cp "$debs/libglstereo-preload_${version}_i386.deb" "$root/tmp/"
cp "$top/tests/c/installed.c" "$top/tests/c/check.h" "$root/tmp/prog/"

# The checks, run inside the root: as root where a person would be root
# (apt-get), as the user "stereo" otherwise.
cat >"$root/tmp/checks.sh" <<'CHECKS'
set -eu
export DEBIAN_FRONTEND=noninteractive LANG=C.UTF-8
failed=0
pass() { echo "PASS: $*"; }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
as_user() { runuser -u stereo -- env HOME=/home/stereo PATH=/usr/local/bin:/usr/bin:/bin "$@"; }
apt_get() { apt-get -q -o DPkg::Lock::Timeout=300 "$@"; }

useradd -m stereo
apt_get update >/dev/null
echo "== apt-get install ./tmp/debs/*.deb"
apt_get install -y /tmp/debs/*.deb
for p in glstereo libglstereo0 libglstereo-dev libglstereo-preload; do
    dpkg -L "$p" | sort >"/tmp/files-$p"
done
cat /tmp/files-* | sort -u >/tmp/files
# Which of them are directories now (dpkg -L lists both).
while read -r f; do [ -d "$f" ] && echo "$f"; done </tmp/files >/tmp/dirs || true

echo "== glstereo-run on PATH, with the installed layer"
w=$(as_user sh -c 'command -v glstereo-run') || true
[ "$w" = /usr/bin/glstereo-run ] && pass "glstereo-run on PATH ($w)" || fail "glstereo-run on PATH: '$w'"
pre=$(as_user glstereo-run -- /usr/bin/printenv LD_PRELOAD 2>&1) || true
case "$pre" in
/usr/lib/*-linux-gnu/glstereo/libglstereo_preload.so) pass "glstereo-run preloads $pre" ;;
*) fail "glstereo-run preloads: $pre" ;;
esac

echo "== man glstereo-run (man-db installed as a user would)"
apt_get install -y man-db >/dev/null
if as_user env MANPAGER=cat MANWIDTH=80 man glstereo-run 2>&1 | grep -q 'glstereo-run.*-m'; then
    pass "man glstereo-run opens"
else
    fail "man glstereo-run: $(as_user env MANPAGER=cat man glstereo-run 2>&1 | head -3)"
fi

echo "== a C program built with pkg-config (gcc, pkg-config installed as a user would)"
apt_get install -y gcc libc6-dev pkg-config >/dev/null
cp -r /tmp/prog /home/stereo/prog && chown -R stereo /home/stereo/prog
flags=$(as_user pkg-config --cflags --libs glstereo) && pass "pkg-config --cflags --libs glstereo: $flags" ||
    fail "pkg-config glstereo"
if as_user sh -c 'cd ~/prog && cc -std=c99 -Wall -Wextra -Werror installed.c $(pkg-config --cflags --libs glstereo) -o installed'; then
    out=$(as_user sh -c 'cd ~/prog && GLSTEREO_BACKEND=egl ./installed' 2>&1) || true
    case "$out" in
    *" passed, 0 failed"*) pass "the C program runs against the installed library: $(echo "$out" | tail -1)" ;;
    *) fail "the C program: $out" ;;
    esac
    multiarch=$(gcc -print-multiarch)
    # /lib is /usr/lib on Debian 12 (merged /usr): the loader may say either.
    ldd /home/stereo/prog/installed | grep -Eq "libglstereo.so.0 => (/usr)?/lib/$multiarch/libglstereo.so.0" &&
        pass "it links /usr/lib/$multiarch/libglstereo.so.0" || fail "ldd: $(ldd /home/stereo/prog/installed)"
else
    fail "cc installed.c \$(pkg-config --cflags --libs glstereo)"
fi

# glxgears -stereo under glstereo-run on Xvfb for a few seconds; $1: label,
# $2: the glxgears to run. Passes when a left and a right eye of one frame
# differ (the PNG encoder is deterministic: equal images give equal files).
gears() {
    dir=/home/stereo/capture-$1
    rm -rf "$dir"
    as_user xvfb-run -a -s '-screen 0 640x480x24' timeout 8 \
        glstereo-run -m side-by-side-half --capture "$dir" "$2" -stereo >/tmp/gears-$1.log 2>&1 || true
    left=$(ls "$dir"/left-*.png 2>/dev/null | sed -n 3p)
    right=$(echo "$left" | sed 's|/left-|/right-|')
    mkdir -p /tmp/shots
    for f in "$left" "$right" "$(echo "$left" | sed 's|/left-|/composite-|')"; do
        [ -f "$f" ] && cp "$f" "/tmp/shots/$1-$(basename "$f")"
    done
    if [ -n "$left" ] && [ -f "$right" ] && ! cmp -s "$left" "$right"; then
        pass "$1 glxgears -stereo: $(ls "$dir" | grep -c '^left-') frames, $(basename "$left") and $(basename "$right") differ"
    else
        fail "$1 glxgears -stereo: $(ls "$dir" 2>&1 | head -5); $(tail -5 /tmp/gears-$1.log)"
    fi
}

echo "== glxgears -stereo under glstereo-run (mesa-utils, xvfb installed as a user would)"
apt_get install -y mesa-utils xvfb xauth >/dev/null
as_user xvfb-run -a timeout 5 glxgears -stereo >/tmp/gears-plain.log 2>&1 || true
grep -q -i "stereo" /tmp/gears-plain.log && echo "(without glstereo-run: $(grep -i stereo /tmp/gears-plain.log | head -1))"
gears amd64 glxgears

if [ -f /tmp/libglstereo-preload_*_i386.deb ]; then
    echo "== a 32-bit program: i386 glxgears"
    dpkg --add-architecture i386
    apt_get update >/dev/null
    apt_get install -y mesa-utils:i386 >/dev/null
    msg=$(as_user xvfb-run -a timeout 5 glstereo-run glxgears -stereo 2>&1) || true
    case "$msg" in
    *"is a 32-bit program"*"libglstereo-preload:i386"*) pass "without the i386 layer: $msg" ;;
    *) fail "without the i386 layer: $msg" ;;
    esac
    apt_get install -y /tmp/libglstereo-preload_*_i386.deb
    dpkg -L libglstereo-preload:i386 | sort >/tmp/files-i386
    while read -r f; do [ -d "$f" ] && echo "$f"; done </tmp/files-i386 >>/tmp/dirs || true
    cat /tmp/files-i386 >>/tmp/files
    gears i386 glxgears
fi

echo "== apt-get purge"
apt_get purge -y glstereo libglstereo0 libglstereo-dev libglstereo-preload \
    $(dpkg-query -W -f='${Package}:${Architecture}\n' 'libglstereo-preload:i386' 2>/dev/null || true)
left=0
while read -r f; do
    [ "$f" = /. ] && continue
    [ -e "$f" ] || [ -L "$f" ] || continue
    if grep -qx "$f" /tmp/dirs && dpkg -S "$f" >/dev/null 2>&1; then
        continue # a directory other packages still own (/usr/lib/..., /usr/share/man/man1)
    fi
    echo "left behind: $f"
    left=$((left + 1))
done </tmp/files
[ "$left" = 0 ] && pass "purge left none of the $(wc -l </tmp/files) paths behind" || fail "purge left $left paths"
echo "$failed checks failed"
exit $((failed > 0))
CHECKS

say "installing the packages and checking them (version $version, $arch${i386:+ and i386's preload})"
status=0
chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    /bin/sh /tmp/checks.sh >>"$log" 2>&1 || status=$?
grep -E '^(PASS|FAIL|left behind|[0-9]+ checks failed)' "$log" >&2 || true
# The frames compared, for a person to look at.
for f in "$root"/tmp/shots/*.png; do
    [ -f "$f" ] && cp "$f" "$base/glstereo-debroot-$$-$(basename "$f")"
done
took=$(( $(date +%s) - start ))
say "exited $status after $((took / 60)) min $((took % 60)) s (log: $log)"
exit "$status"
