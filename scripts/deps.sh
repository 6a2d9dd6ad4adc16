#!/usr/bin/env bash
# Installs the Debian 12 packages throng needs that are missing (apt-get; sudo when not root).
# Sourced by scripts/demo.sh and scripts/test.sh; safe to run again (installs nothing when complete).
set -euo pipefail

THRONG_DEB_PACKAGES=(
  cmake ninja-build clang libclang-rt-14-dev g++ pkg-config
  librecast-dev nlohmann-json3-dev libcli11-dev libfmt-dev libtbb-dev libsqlite3-dev sqlite3
  libboost-dev libzstd-dev librapidcheck-dev libgtest-dev libgmock-dev libbenchmark-dev libtinygltf-dev
  libopenmpi-dev openmpi-bin
  python3 python3-dev python3-numpy python3-matplotlib python3-pandas python3-pytest python3-hypothesis pybind11-dev
  python3-shapely python3-jsonschema
  python3-venv python3-pip python3-setuptools python3-wheel
  universal-ctags
  man-db zsh dpkg-dev lintian
  chromium nodejs
)

throng_install_deps() {
  local missing=()
  for p in "${THRONG_DEB_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  # npm: Debian's package, unless a node that bundles it (e.g. NodeSource's nodejs) is installed.
  command -v npm >/dev/null 2>&1 || missing+=(npm)
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "throng: installing missing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# Configures and builds into build/ (Release, clang when present so libFuzzer targets build too).
throng_build() {
  local root="$1"; shift
  local cc=gcc cxx=g++
  if command -v clang++ >/dev/null 2>&1; then cc=clang; cxx=clang++; fi
  if [ ! -f "$root/build/CMakeCache.txt" ]; then
    CC=$cc CXX=$cxx cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
  fi
  cmake --build "$root/build" -j "$(nproc)"
}

# Builds the browser viewer (web/ → web/dist/, which `throng serve` serves): `npm ci` when
# web/node_modules is missing or older than package-lock.json, then `npm run build`. Its tools
# (Vite 6, playwright-core 1.61) run on Debian 12's own nodejs 18. Returns 1, saying what is missing
# and how to get it, when node ≥ 18 or npm is not there or npm fails (offline): the viewer and its
# tests are part of the build, and ctest fails rather than skips without them.
throng_build_web() {
  local root="$1"
  local web="$root/web"
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "throng: error: node/npm not found: the browser viewer (web/dist) cannot be built; install them with: apt-get install nodejs npm" >&2
    return 1
  fi
  if ! node -e 'process.exit(Number(process.versions.node.split(".")[0]) >= 18 ? 0 : 1)'; then
    echo "throng: error: node $(node --version) is too old for the browser viewer's build (needs 18 or newer; Debian 12's nodejs is 18.20): apt-get install nodejs" >&2
    return 1
  fi
  if [ ! -d "$web/node_modules" ] || [ "$web/package-lock.json" -nt "$web/node_modules" ]; then
    echo "throng: installing the viewer's npm packages (npm ci in web/)"
    if ! (cd "$web" && npm ci --no-audit --no-fund); then
      echo "throng: error: npm ci failed in web/ (see above; offline? it needs the npm registry once): the browser viewer cannot be built" >&2
      return 1
    fi
    touch "$web/node_modules"
  fi
  echo "throng: building the browser viewer (web/dist)"
  if ! (cd "$web" && npm run build --silent); then
    echo "throng: error: the browser viewer's build failed (see above): web/dist is not built" >&2
    return 1
  fi
}
