#!/usr/bin/env bash
# The fresh-machine check (issue 9): builds a minimal Debian 12 root with mmdebstrap, copies this
# work tree into it, and runs there, as root, the README's two commands exactly as written (the
# first two ```sh blocks of README.md "Two commands"): install, build and render the demo; then
# the test suite, with a copy of ../shared beside the tree. A package that install-deps.sh forgets
# fails here instead of on a user's machine.
#
#   bash scripts/check-fresh-install.sh [--keep]
#
# Needs root (chroot, mount). Uses the machine's own apt sources (INSITU_FRESH_SOURCES overrides:
# a sources file, or a mirror URI). --keep leaves the root in place and prints its path.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
keep=0
[ "${1:-}" = "--keep" ] && keep=1

die() { echo "check-fresh-install: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || die "must run as root (chroot and mount)"
if ! command -v mmdebstrap >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mmdebstrap >/dev/null
fi

# The README's commands: the first two ```sh blocks after the "## Two commands" heading.
readme_block() {  # the N-th ```sh block after "## Two commands", blank lines dropped
  awk -v want="$1" '/^## Two commands/{on=1} on && /^```sh$/{n++; block=(n==want); next}
                    block && /^```$/{exit} block && NF{print}' README.md
}
first=$(readme_block 1)
second=$(readme_block 2)
[ -n "$first" ] && [ -n "$second" ] || die "README.md: no two \`\`\`sh blocks under '## Two commands'"

sources=${INSITU_FRESH_SOURCES:-}
if [ -z "$sources" ]; then
  if [ -s /etc/apt/sources.list.d/debian.sources ]; then sources=/etc/apt/sources.list.d/debian.sources
  elif [ -s /etc/apt/sources.list ]; then sources=/etc/apt/sources.list
  else sources=http://deb.debian.org/debian; fi
fi

root=$(mktemp -d "${TMPDIR:-/tmp}/insitu-fresh-root.XXXXXX")
cleanup() {
  mountpoint -q "$root/proc" && umount -l "$root/proc"
  if [ "$keep" -eq 1 ]; then echo "check-fresh-install: root kept at $root" >&2; else rm -rf "$root"; fi
}
trap cleanup EXIT

start=$(date +%s)
echo "check-fresh-install: building a minimal Debian 12 root in $root (sources: $sources)"
mmdebstrap --quiet --variant=minbase --mode=root bookworm "$root" "$sources"
mount -t proc proc "$root/proc"
# Every installed Debian machine has an /etc/hosts (the installer or the cloud image writes it; no
# package does), and mmdebstrap's root has none: without it "localhost" does not resolve, and
# selenium cannot reach chromedriver, so the studio's browser test skipped here (found 2026-11-24).
printf '127.0.0.1\tlocalhost\n::1\tlocalhost ip6-localhost ip6-loopback\n' > "$root/etc/hosts"

# The work tree as a fresh clone would have it (tracked and new files, nothing ignored).
mkdir -p "$root/root/insitu"
git -C "$repo" ls-files -z --cached --others --exclude-standard |
  (cd "$repo" && tar --null -T - -cf -) | tar -xf - -C "$root/root/insitu"
# ../shared beside it, as on the machine (a copy: a few MB), so that the tests that need the shared
# HDRIs and meshes run here too instead of skipping.
if [ -d "$repo/../shared" ]; then cp -r -L "$repo/../shared" "$root/root/shared"; fi  # -L: a linked ../shared is copied, not linked

in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 /bin/bash -euo pipefail -c "cd /root/insitu && $1"
}
# Each stage's time is printed: a slow run says whether the root, the install and build, or the
# tests took it (e574ef9's stage took 1362 s, earlier ones 649-811 s, and nothing said where).
stage=$start  # the root counts from its mmdebstrap
lap() { echo "check-fresh-install: $1 in $(( $(date +%s) - stage )) s"; stage=$(date +%s); }
lap "root built"
echo "check-fresh-install: README command 1: $first"
in_root "$first" || die "the README's first command failed on a fresh Debian 12 root"
in_root "test -s scenes/demo/out/composite.png" || die "the first command rendered no scenes/demo/out/composite.png"
lap "README command 1 (install, build, demo) passed"
# Packages that tests need only in CI (INSITU_CI_PACKAGES, from .ci/run: Debian's blender, whose
# Cycles the Blender tests render with), installed after the user's first command, never by it.
if [ -n "${INSITU_CI_PACKAGES:-}" ]; then
  in_root "DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $INSITU_CI_PACKAGES >/dev/null" ||
    die "could not install $INSITU_CI_PACKAGES in the fresh root"
  lap "CI's own packages ($INSITU_CI_PACKAGES) installed"
fi
echo "check-fresh-install: README command 2: $second"
in_root "$second" || die "the README's test command failed on a fresh Debian 12 root"
lap "README command 2 (the test suite) passed"
echo "check-fresh-install: passed in $(( $(date +%s) - start )) s"
