#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then builds examples/ against the installed package as
# a host program would (CMake's find_package, and pkg-config), and runs them on the demo scene:
# the README's C example, and render_and_cancel, which renders and cancels a second render midway.
# The installed CLI and Python module run too. Usage: check-install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The demo at 8 samples per pixel (a copy: the source tree is not written): the examples' renders
# are checked for running and writing, not for their noise (144 spp took 3 × 30 s).
cp -r "$source/scenes/demo" "$work/demo"
rm -rf "$work/demo/out"
sed -i 's/"spp": 144/"spp": 8/' "$work/demo/scene.json"
grep -q '"spp": 8' "$work/demo/scene.json" || { echo "check-install: the demo's spp was not 144"; exit 1; }
demo=$work/demo/scene.json
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in include/insitu/insitu.h lib/libinsitu.so lib/cmake/insitu/insituConfig.cmake lib/pkgconfig/insitu.pc bin/insitu; do
  [ -e "$prefix/$f" ] || { echo "check-install: $f was not installed"; exit 1; }
done
echo "== CMake: find_package(insitu)"
cmake -S "$source/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/examples" > "$work/build.log" || { cat "$work/build.log"; exit 1; }
"$work/examples/minimal" "$demo" "$work/minimal.png"
"$work/examples/render_and_cancel" "$demo" "$work/render.png"
[ -s "$work/minimal.png" ] && [ -s "$work/render.png" ] && [ -s "$work/render.png.report.json" ]
echo "== pkg-config"
PKG_CONFIG_PATH=$prefix/lib/pkgconfig cc -std=c99 -Wall -Werror "$source/examples/minimal.c" \
  $(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags --libs insitu) -o "$work/minimal-pc"
# As the README says to build it, with no LD_LIBRARY_PATH: insitu.pc carries the run path.
env -u LD_LIBRARY_PATH "$work/minimal-pc" "$demo" "$work/minimal-pc.png"
echo "== the installed CLI and Python module"
"$prefix/bin/insitu" --version
PYTHONPATH=$prefix/lib/python3/dist-packages python3 -c "import insitu; print('python module', insitu.version())"
echo "check-install: OK"
