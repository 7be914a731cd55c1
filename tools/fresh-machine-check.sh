#!/usr/bin/env bash
# Proves the README's quick start on a fresh machine: builds a minimal Debian 12 root
# (debootstrap --variant=minbase bookworm, cached between runs), puts a clean clone of HEAD in it,
# runs the README's two quick-start commands exactly as written, then both again (a second run
# must be fast and green), then the first once more after breaking the set-up as an interrupted
# run would (a half-configured build folder, a package unpacked but not configured), and reports
# each exit code and time. Exit 0 when every run exits 0 and a PNG is under out/.
#
#   tools/fresh-machine-check.sh [--keep]      (as root; needs debootstrap, git, unshare)
#
#   --keep                 leave the root in place afterwards (its path is printed)
#   RELIEF_FRESH_CACHE     where the pristine root and the downloaded .deb files are kept
#                          (default /var/cache/relief-fresh-machine)
#   RELIEF_DEBIAN_MIRROR   the Debian mirror (default: the host's, else http://deb.debian.org/debian)
#
# Too slow for .ci/run (10-30 minutes); run it before resolving anything that touches the
# dependencies or the set-up. Only the .deb download cache is shared between runs: every run starts
# from the pristine minbase root, with no package of relief's installed.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)

keep=0
case "${1:-}" in
  --keep) keep=1 ;;
  "") ;;
  -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "fresh-machine-check: unknown option '$1' (try --help)" >&2; exit 2 ;;
esac
[ "$(id -u)" -eq 0 ] || { echo "fresh-machine-check: run as root (debootstrap and chroot need it)" >&2; exit 2; }
for tool in debootstrap git unshare chroot; do
  command -v "$tool" >/dev/null || {
    echo "fresh-machine-check: '$tool' is missing (apt-get install debootstrap git util-linux)" >&2; exit 2; }
done

cache=${RELIEF_FRESH_CACHE:-/var/cache/relief-fresh-machine}
host_mirror=$(grep -hoE '^(deb +|URIs: +)https?://[^ ]+/debian/?( |$)' /etc/apt/sources.list \
                /etc/apt/sources.list.d/* 2>/dev/null | head -1 | grep -oE 'https?://[^ ]+' || true)
mirror=${RELIEF_DEBIAN_MIRROR:-${host_mirror:-http://deb.debian.org/debian}}
pristine=$cache/bookworm-minbase.tar
mkdir -p "$cache/archives/partial"

# The pristine root: made once, kept as a tarball; a half-made one is never kept.
if [ ! -f "$pristine" ]; then
  echo "== debootstrap --variant=minbase bookworm from $mirror (once; cached in $pristine)"
  stage=$(mktemp -d /var/tmp/relief-debootstrap.XXXXXX)
  t0=$(date +%s)
  debootstrap --variant=minbase bookworm "$stage" "$mirror" >"$cache/debootstrap.log" 2>&1 || {
    tail -20 "$cache/debootstrap.log" >&2; rm -rf "$stage"
    echo "fresh-machine-check: debootstrap failed (log: $cache/debootstrap.log)" >&2; exit 1; }
  tar -C "$stage" -cf "$pristine.tmp" . && mv "$pristine.tmp" "$pristine"
  rm -rf "$stage"
  echo "   made in $(( $(date +%s) - t0 )) s"
fi

root=$(mktemp -d /var/tmp/relief-fresh-root.XXXXXX)
cleanup() { [ "$keep" -eq 1 ] && echo "root kept: $root" || rm -rf "$root"; }
trap cleanup EXIT
tar -C "$root" -xf "$pristine"
# mktemp makes folders 0700 (the root's, and debootstrap's, whose ./ the tar keeps), and the root
# becomes the chroot's /: a package's own user (munge's postinst runs su munge) could not reach
# /bin/sh. A machine's / is 0755.
chmod 755 "$root"
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
# The machine's own certificate authorities (what its way out may need: a TLS-inspecting proxy's),
# for npm's registry, which is HTTPS where apt's mirror is not: the host's local ones, given to
# Node.js as the host gives them to its own npm (a machine with a direct way out needs none).
cat /usr/local/share/ca-certificates/*.crt > "$root/etc/host-local-ca.crt" 2>/dev/null || true
# The machine's own name resolves, as Debian's installer writes it (debootstrap writes no hosts file).
printf '127.0.0.1\tlocalhost\n127.0.1.1\t%s\t%s\n::1\tlocalhost ip6-localhost ip6-loopback\n' \
  "$(hostname -f 2>/dev/null || hostname)" "$(hostname -s)" > "$root/etc/hosts"

# A clean clone of HEAD: what is committed, nothing of the work tree.
head=$(git -C "$repo" rev-parse HEAD)
git clone -q --no-hardlinks "$repo" "$root/root/relief"
git -C "$root/root/relief" checkout -q --detach "$head"
echo "== clean clone of $(git -C "$repo" rev-parse --short HEAD) in $root/root/relief"

# The quick-start commands, exactly as the README writes them: the lines of the first code block
# under "## Quick start", each without its trailing comment.
mapfile -t commands < <(awk '
  /^## Quick start/ { in_section = 1; next }
  in_section && /^```/ { if (in_block) exit; in_block = 1; next }
  in_section && in_block && NF { sub(/[ \t]+#.*$/, ""); print }' "$repo/README.md")
[ ${#commands[@]} -eq 2 ] || {
  echo "fresh-machine-check: expected two quick-start commands in README.md, found ${#commands[@]}" >&2
  exit 1; }

# Runs one command in the root, in a private mount namespace (its mounts vanish with it).
run_in_root() {  # run_in_root LOG COMMAND
  local log=$1 cmd=$2
  unshare --mount --propagation private -- bash -c '
    set -e
    root=$1; cache=$2; cmd=$3
    # The root as a mount point of its own, as on a real machine: bubblewrap (the render'"'"'s
    # sandbox) pivots into a new root, which needs the current one to be a mount point.
    mount --bind "$root" "$root"
    mount -t proc proc "$root/proc"
    mount --rbind /dev "$root/dev"
    # /sys with what is mounted below it, cgroups included, as on a real machine (slurmd needs them).
    mount --rbind /sys "$root/sys"
    mount --bind "$cache/archives" "$root/var/cache/apt/archives"
    exec chroot "$root" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 NODE_EXTRA_CA_CERTS=/etc/host-local-ca.crt \
      PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      /bin/bash -c "cd /root/relief && $cmd"' _ "$root" "$cache" "$cmd" >"$log" 2>&1
}

failed=0
report=()
for pass in 1 2; do
  for i in "${!commands[@]}"; do
    cmd=${commands[$i]}
    log=$cache/run-$pass-$((i + 1)).log
    echo "== run $pass: $cmd"
    t0=$(date +%s)
    rc=0; run_in_root "$log" "$cmd" || rc=$?
    secs=$(( $(date +%s) - t0 ))
    tail -3 "$log" | sed 's/^/   | /'
    report+=("$(printf 'run %d  exit %-3d %5d s  %s' "$pass" "$rc" "$secs" "$cmd")")
    [ "$rc" -eq 0 ] || { failed=1; echo "   (whole log: $log)"; }
  done
done

# An interrupted earlier run: configure stopped before writing the build system (CMakeCache.txt
# without a Makefile), and dpkg stopped between unpacking and configuring a package.
echo "== breaking the set-up as an interrupted run would"
run_in_root "$cache/break.log" '
  set -e
  rm -f build/Makefile out/*.png
  deb=$(ls /var/cache/apt/archives/povray_*.deb | head -1)
  dpkg --remove --force-depends povray >/dev/null
  dpkg --unpack "$deb" >/dev/null
  dpkg-query -W -f="povray: \${Status}\n" povray' || { echo "   could not break the set-up (log: $cache/break.log)"; failed=1; }
sed 's/^/   | /' "$cache/break.log"
cmd=${commands[0]}
echo "== run 3 (recovering): $cmd"
t0=$(date +%s)
rc=0; run_in_root "$cache/run-3-1.log" "$cmd" || rc=$?
secs=$(( $(date +%s) - t0 ))
tail -3 "$cache/run-3-1.log" | sed 's/^/   | /'
report+=("$(printf 'run 3  exit %-3d %5d s  %s  (after an interrupted run)' "$rc" "$secs" "$cmd")")
[ "$rc" -eq 0 ] || { failed=1; echo "   (whole log: $cache/run-3-1.log)"; }

pngs=$(find "$root/root/relief/out" -name '*.png' -printf '%P (%s bytes)\n' 2>/dev/null || true)
echo
echo "== fresh-machine-check: Debian $(cat "$root/etc/debian_version") minbase, clone of $head"
printf '%s\n' "${report[@]}"
if [ -n "$pngs" ]; then
  echo "PNG under out/: $pngs"
else
  echo "no PNG under out/"; failed=1
fi
[ "$failed" -eq 0 ] && echo "fresh-machine-check: PASS" || echo "fresh-machine-check: FAIL"
exit "$failed"
