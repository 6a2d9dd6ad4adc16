#!/usr/bin/env bash
# ctest deb_package: the Debian package of the build (cmake/ThrongCPack.cmake, docs/install.md).
#   1. `cpack -G DEB` from the build directory (installs the built tree; nothing is rebuilt when
#      the build is up to date) writes throng_<version>_amd64.deb;
#   2. dpkg-deb -c: the program, the shared libraries and their SONAME links, headers, CMake package,
#      pkg-config file, scenarios, verification scripts, the viewer, man pages for throng and every
#      command, bash and zsh completions, copyright and changelog, all under /usr;
#   3. dpkg-deb -f: Depends names Debian's libraries (from dpkg-shlibdeps), maintainer, section;
#   4. lintian reports no error (E:) — its warnings are printed;
#   5. the package extracted with dpkg-deb -x runs its own museum.json from <dir>/usr/share/throng
#      (libraries found through the binary's $ORIGIN/../lib RUNPATH: no LD_LIBRARY_PATH).
# Never installs the package on this machine.
#   6. examples/embed builds with the extracted package's CMake package (CMAKE_PREFIX_PATH=<dir>/usr)
#      and runs on its museum.json.
#   deb_package_test.sh BUILD_DIR VERSION SOURCE_DIR CXX_COMPILER
set -euo pipefail
build="$1"
version="$2"
src="$3"
cxx="$4"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/throng-deb-XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
for tool in cpack dpkg-deb dpkg-shlibdeps lintian; do
  command -v "$tool" > /dev/null || { echo "FAIL: $tool not found: apt-get install dpkg-dev lintian (scripts/deps.sh)"; exit 1; }
done
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

echo "== cpack -G DEB"
(cd "$build" && cpack -G DEB -B "$tmp/out") > "$tmp/cpack.log" 2>&1 || { cat "$tmp/cpack.log"; exit 1; }
deb="$tmp/out/throng_${version}_amd64.deb"
test -f "$deb" || { echo "FAIL: $deb not written:"; ls "$tmp/out"; exit 1; }

echo "== contents"
dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' > "$tmp/contents"
expect=(/usr/bin/throng /usr/lib/libthrong_sim.so.0.1 /usr/lib/libthrong_core.so "/usr/lib/libthrong_io.so.${version}"
        /usr/include/throng/sim/world.hpp /usr/include/throng/throng_link.h /usr/lib/cmake/throng/throngConfig.cmake
        /usr/lib/cmake/throng/throngTargets.cmake /usr/lib/pkgconfig/throng.pc
        /usr/share/throng/scenarios/museum.json /usr/share/throng/scenarios/schema/scenario.schema.json
        /usr/share/throng/scripts/verify.py /usr/share/throng/verification/rimea/01-corridor.json
        /usr/share/throng/web/index.html /usr/share/man/man1/throng.1.gz
        /usr/share/bash-completion/completions/throng /usr/share/zsh/vendor-completions/_throng
        /usr/share/doc/throng/copyright /usr/share/doc/throng/changelog.gz)
for command in $("$build/apps/throng/throng" --help | awk '/^Subcommands:/{on=1; next} on && /^  [a-z]/{print $1} on && /^$/{exit}'); do
  expect+=("/usr/share/man/man1/throng-$command.1.gz")
done
for path in "${expect[@]}"; do
  grep -qxF "$path" "$tmp/contents" || fail "the package lacks $path"
done
grep -v '^/usr/' "$tmp/contents" | grep -v '^/$' && fail "files outside /usr"
grep -q '__pycache__\|\.pyc$' "$tmp/contents" && fail "Python bytecode in the package"

echo "== control fields"
depends="$(dpkg-deb -f "$deb" Depends)"
echo "Depends: $depends"
for lib in libc6 libstdc++6 libtbb12 libsqlite3-0 libzstd1 librecast1; do
  tr ',' '\n' <<< "$depends" | awk '{print $1}' | grep -qxF "$lib" || fail "Depends lacks $lib"
done
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version is not $version"
[ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "no Maintainer"
[ "$(dpkg-deb -f "$deb" Section)" = "science" ] || fail "Section is not science"

echo "== lintian"
lintian --no-tag-display-limit "$deb" > "$tmp/lintian.txt" 2>&1 || true
grep -E '^[EW]: ' "$tmp/lintian.txt" || true
grep -q '^E: ' "$tmp/lintian.txt" && fail "lintian reports errors"

echo "== the extracted package runs its own scenario"
dpkg-deb -x "$deb" "$tmp/root"
(cd "$tmp" && "$tmp/root/usr/bin/throng" run "$tmp/root/usr/share/throng/scenarios/museum.json" --duration 5 \
                --out "$tmp/museum.sqlite" --json > "$tmp/run.json") || fail "throng run from the extracted package failed"
grep -q "\"agents_spawned\":[1-9]" "$tmp/run.json" || fail "throng run printed no summary: $(cat "$tmp/run.json")"
"$tmp/root/usr/bin/throng" verify --list --suite nist > "$tmp/verify.txt" || fail "throng verify --list failed"
grep -q '^nist-' "$tmp/verify.txt" || fail "throng verify --list listed no NIST test"
man -l "$tmp/root/usr/share/man/man1/throng-run.1.gz" > /dev/null 2>&1 || fail "man -l throng-run.1.gz failed"

echo "== examples/embed against the extracted package's CMake package"
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
if cmake -S "$src/examples/embed" -B "$tmp/embed" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" \
         -DCMAKE_PREFIX_PATH="$tmp/root/usr" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF > "$tmp/embed.log" 2>&1 &&
   grep -q "throng_DIR:PATH=$tmp/root/usr/" "$tmp/embed/CMakeCache.txt" &&
   cmake --build "$tmp/embed" >> "$tmp/embed.log" 2>&1 &&
   "$tmp/embed/throng_embed" "$tmp/root/usr/share/throng/scenarios/museum.json" 2 > "$tmp/embed.out"; then
  grep -Eq '^t = +2\.0 s  agents [1-9]' "$tmp/embed.out" || fail "throng_embed printed: $(cat "$tmp/embed.out")"
else
  cat "$tmp/embed.log"
  fail "examples/embed does not build or run against the package"
fi

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "ok: $(basename "$deb"), $(wc -l < "$tmp/contents") paths, no lintian error"
