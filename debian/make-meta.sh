#!/bin/sh
# Writes debian/changelog and debian/copyright for `make deb` (neither is
# kept in git: both are made from the project's own records each time).
#
# changelog: the version in Cargo.toml and that version's section of
#   CHANGELOG.md (each paragraph or "- " item one entry, wrapped for
#   Debian's 80 columns), dated by the last commit that touched either
#   (so a rebuild of the same commit gives the same packages).
# copyright: machine-readable (DEP-5): the project's licence and, from
#   `cargo tree`, every crate linked into the binaries with its licence.
set -eu
cd "$(dirname "$0")/.."

version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
[ -n "$version" ] || { echo "make-meta.sh: no version in Cargo.toml" >&2; exit 1; }
maintainer=$(sed -n 's/^Maintainer: //p' debian/control)
date=$(git log -1 --format=%aD -- CHANGELOG.md Cargo.toml 2>/dev/null || true)
[ -n "$date" ] || date=$(date -R)
heading=$(grep -m 1 "^## $version\( \|$\)" CHANGELOG.md || true)
[ -n "$heading" ] || {
    echo "make-meta.sh: CHANGELOG.md has no section \"## $version\"" >&2
    exit 1
}

{
    printf 'glstereo (%s) bookworm; urgency=medium\n\n' "$version"
    printf '  * %s (CHANGELOG.md).\n' "$(echo "$heading" | sed 's/^## /glstereo /')"
    awk -v head="$heading" '
        $0 == head { inside = 1; next }
        inside && /^## / { exit }
        !inside { next }
        function flush() { if (item != "") print item; item = "" }
        /^[[:space:]]*$/ { flush(); next }
        /^- / { flush(); item = substr($0, 3); next }
        { sub(/^[[:space:]]+/, ""); item = (item == "" ? $0 : item " " $0) }
        END { flush() }
    ' CHANGELOG.md | while IFS= read -r item; do
        printf '%s\n' "$item" | fold -s -w 74 | sed -e 's/[[:space:]]*$//' \
            -e '1s/^/  * /' -e '2,$s/^/    /'
    done
    printf '\n -- %s  %s\n' "$maintainer" "$date"
} >debian/changelog

year=$(git log --reverse --format=%ad --date=format:%Y 2>/dev/null | head -n 1)
last=$(git log -1 --format=%ad --date=format:%Y 2>/dev/null || true)
[ -n "$year" ] || year=$(date +%Y)
[ -n "$last" ] && [ "$last" != "$year" ] && year="$year-$last"
crates=$(cargo tree --locked --offline -e normal,no-proc-macro -p glstereo -p glstereo-preload \
    --prefix none -f '{p}|{l}' 2>/dev/null | sed 's/ (\*)$//' | grep -v '^glstereo' | sort -u)
[ -n "$crates" ] || crates=$(cargo tree --locked -e normal,no-proc-macro -p glstereo \
    -p glstereo-preload --prefix none -f '{p}|{l}' | sed 's/ (\*)$//' | grep -v '^glstereo' | sort -u)

{
    cat <<EOT
Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
Upstream-Name: glstereo
Upstream-Contact: $maintainer
Source: https://github.com/glstereo/glstereo
Comment: The binaries link these Rust crates from crates.io statically
 (cargo tree -e normal, made when the packages were built); each is used
 under the licence named, or one of them where it offers a choice:
EOT
    printf '%s\n' "$crates" | sed -e 's/|/: /' -e 's/^/  /' -e 's/^ *$/ ./' \
        -e 's/^/ /' | sed 's/^  */ /'
    cat <<EOT
 .
 jpeg-encoder's JPEG code is based in part on the work of the Independent
 JPEG Group (licence IJG below).

Files: *
Copyright: $year glstereo developers
License: MIT or Apache-2.0

License: MIT
 Permission is hereby granted, free of charge, to any person obtaining a
 copy of this software and associated documentation files (the "Software"),
 to deal in the Software without restriction, including without limitation
 the rights to use, copy, modify, merge, publish, distribute, sublicense,
 and/or sell copies of the Software, and to permit persons to whom the
 Software is furnished to do so, subject to the following conditions:
 .
 The above copyright notice and this permission notice shall be included in
 all copies or substantial portions of the Software.
 .
 THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
 IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
 FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL
 THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
 LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING
 FROM, OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER
 DEALINGS IN THE SOFTWARE.

License: Apache-2.0
 On Debian systems, the full text of the Apache License, Version 2.0 is in
 /usr/share/common-licenses/Apache-2.0.

License: ISC
 Permission to use, copy, modify, and/or distribute this software for any
 purpose with or without fee is hereby granted, provided that the above
 copyright notice and this permission notice appear in all copies.
 .
 THE SOFTWARE IS PROVIDED "AS IS" AND THE AUTHOR DISCLAIMS ALL WARRANTIES
 WITH REGARD TO THIS SOFTWARE INCLUDING ALL IMPLIED WARRANTIES OF
 MERCHANTABILITY AND FITNESS. IN NO EVENT SHALL THE AUTHOR BE LIABLE FOR
 ANY SPECIAL, DIRECT, INDIRECT, OR CONSEQUENTIAL DAMAGES OR ANY DAMAGES
 WHATSOEVER RESULTING FROM LOSS OF USE, DATA OR PROFITS, WHETHER IN AN
 ACTION OF CONTRACT, NEGLIGENCE OR OTHER TORTIOUS ACTION, ARISING OUT OF
 OR IN CONNECTION WITH THE USE OR PERFORMANCE OF THIS SOFTWARE.

License: IJG
 The terms of the Independent JPEG Group's software licence (the LEGAL
 ISSUES section of libjpeg's README): use, copying, modification and
 distribution are permitted, with or without fee, provided that a binary
 distribution's documentation states that the software is based in part on
 the work of the Independent JPEG Group (stated above); the software is
 provided "as is", without warranty.
EOT
} >debian/copyright
