#!/bin/bash
# Fetch and unpack the Debian kernel for the vcan micro-VM (docs/can.md#vcan-run).
# Idempotent; prints the cache directory holding vmlinuz + modules. Once a
# kernel is cached it is reused without asking apt (CVT_VM_REFRESH=1 to
# re-resolve linux-image-amd64 and fetch a newer one).
#
#   hil/vm/fetch-kernel.sh            # into $CVT_VM_CACHE or ~/.cache/cvtplant-vm
#
# The kernel is the package linux-image-amd64 depends on (Debian 12: 6.1.x),
# fetched with `apt-get download` (no root needed, no install) and unpacked
# with `dpkg -x`. Its modules are uncompressed .ko files.
set -euo pipefail
cache=${CVT_VM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/cvtplant-vm}
mkdir -p "$cache"
# Fast path: a complete kernel is cached (CVT_VM_REFRESH=1 re-resolves it).
if [ "${CVT_VM_REFRESH:-0}" != 1 ] && [ -e "$cache/current/.complete" ]; then
  readlink -f "$cache/current"
  exit 0
fi
pkg=$(apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/ {print $2; exit}')
if [ -z "$pkg" ]; then
  echo "fetch-kernel: cannot resolve linux-image-amd64's kernel package (apt-get update?)" >&2
  exit 1
fi
dest=$cache/$pkg
if [ ! -e "$dest/.complete" ]; then
  tmp=$(mktemp -d "$cache/.fetch.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  (cd "$tmp" && apt-get download "$pkg" >&2)
  deb=$(ls "$tmp"/*.deb)
  mkdir -p "$tmp/root"
  dpkg -x "$deb" "$tmp/root"
  dpkg-deb -f "$deb" Version > "$tmp/root/.version"
  rm -rf "$dest"
  mv "$tmp/root" "$dest"
  touch "$dest/.complete"
  echo "fetch-kernel: unpacked $(basename "$deb") into $dest" >&2
fi
ln -sfn "$(basename "$dest")" "$cache/current"
echo "$dest"
