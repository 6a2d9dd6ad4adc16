#!/usr/bin/env bash
# ctest install_tree: the installed tree works without the source or build tree (docs/install.md).
#   1. `cmake --install BUILD --prefix P` into a temporary prefix;
#   2. the installed program runs a bundled scenario from P/share/throng and lists the
#      verification tests (P/share/throng/scripts/verify.py) and plots its recording
#      (P/share/throng/scripts/plot.py, P/share/throng/python/throng); the schema, man pages and
#      completions are there;
#   3. examples/embed is configured with only P on CMAKE_PREFIX_PATH (find_package(throng CONFIG),
#      no package registry), built and run on P's museum.json;
#   4. a one-file program is compiled and linked through pkg-config (P/lib*/pkgconfig/throng.pc)
#      and run.
# Any missing install rule, package file or header makes one of these fail.
#   install_tree_test.sh BUILD_DIR SOURCE_DIR CXX_COMPILER
set -euo pipefail
build="$1"
src="$2"
cxx="$3"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/throng-install-XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
step() { echo "== $*"; }

step "cmake --install $build --prefix $prefix"
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; exit 1; }

step "installed throng runs the installed museum.json"
cd "$tmp"
"$prefix/bin/throng" run "$prefix/share/throng/scenarios/museum.json" --duration 5 --out "$tmp/museum.sqlite" --quiet
test -s "$tmp/museum.sqlite"
"$prefix/bin/throng" verify --list --suite rimea > "$tmp/verify.txt"
grep -q '^rimea-1 ' "$tmp/verify.txt" || { echo "throng verify --list did not list rimea-1"; cat "$tmp/verify.txt"; exit 1; }
"$prefix/bin/throng" plot "$tmp/museum.sqlite" --out "$tmp/plots" --what trajectories,density > "$tmp/plot.txt"
test -s "$tmp/plots/trajectories.png" && test -s "$tmp/plots/density.png" \
  || { echo "throng plot did not write its PNGs from the installed scripts"; cat "$tmp/plot.txt"; exit 1; }
for f in share/throng/scenarios/schema/scenario.schema.json share/man/man1/throng.1.gz share/man/man1/throng-run.1.gz \
         share/bash-completion/completions/throng share/zsh/vendor-completions/_throng; do
  test -f "$prefix/$f" || { echo "$f is not installed"; exit 1; }
done

step "examples/embed against the installed package only"
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
cmake -S "$src/examples/embed" -B "$tmp/embed" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF > "$tmp/embed.log" \
  || { cat "$tmp/embed.log"; exit 1; }
grep -q "throng_DIR:PATH=$prefix/" "$tmp/embed/CMakeCache.txt" \
  || { echo "find_package(throng) did not use the installed package:"; grep throng_DIR "$tmp/embed/CMakeCache.txt"; exit 1; }
cmake --build "$tmp/embed" > "$tmp/embed-build.log" || { cat "$tmp/embed-build.log"; exit 1; }
"$tmp/embed/throng_embed" "$prefix/share/throng/scenarios/museum.json" 3 > "$tmp/embed.out"
cat "$tmp/embed.out"
grep -Eq '^t = +3\.0 s  agents [1-9][0-9]*$' "$tmp/embed.out" || { echo "throng_embed did not reach 3 s with agents"; exit 1; }

step "a program built through pkg-config"
pcdir="$(dirname "$(find "$prefix" -name throng.pc | head -n 1)")"
test -f "$pcdir/throng.pc" || { echo "throng.pc is not installed"; exit 1; }
cat > "$tmp/one.cpp" <<'CPP'
#include <cstdio>
#include "throng/io/scenario_loader.hpp"
int main(int argc, char** argv) {
  auto loaded = throng::io::loadScenarioFile(argv[1]);
  if (!loaded) return 1;
  std::printf("populations %zu\n", loaded.value().desc.populations.size());
  return 0;
}
CPP
flags="$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs throng)"
# shellcheck disable=SC2086
"$cxx" -std=c++20 "$tmp/one.cpp" -o "$tmp/one" $flags
LD_LIBRARY_PATH="$(PKG_CONFIG_PATH="$pcdir" pkg-config --variable=libdir throng)" \
  "$tmp/one" "$prefix/share/throng/scenarios/museum.json" > "$tmp/one.out"
grep -Eq '^populations [1-9]' "$tmp/one.out" || { echo "the pkg-config program printed:"; cat "$tmp/one.out"; exit 1; }
echo "ok: installed tree, CMake package and pkg-config file work"
