#!/usr/bin/env bash
# Installs the Debian 12 packages throng needs that are missing (apt-get; sudo when not root).
# Sourced by scripts/demo.sh and scripts/test.sh; safe to run again (installs nothing when complete).
set -euo pipefail

THRONG_DEB_PACKAGES=(
  cmake ninja-build clang libclang-rt-14-dev g++ pkg-config
  librecast-dev nlohmann-json3-dev libcli11-dev libfmt-dev libtbb-dev libsqlite3-dev sqlite3
  libboost-dev libzstd-dev librapidcheck-dev libgtest-dev libgmock-dev libbenchmark-dev libtinygltf-dev
  libopenmpi-dev openmpi-bin
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
# web/node_modules is missing or older than package-lock.json, then `npm run build`. Without
# node/npm, or when npm fails (offline), it says so and returns 0 (the C++ build and tests do not need it).
throng_build_web() {
  local root="$1"
  local web="$root/web"
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "throng: node/npm not found: the browser viewer (web/dist) is not built (apt-get install nodejs npm)"
    return 0
  fi
  # Vite 8 and playwright-core need node ≥ 20.19 (Debian 12's own nodejs is 18).
  if ! node -e 'const [a,b]=process.versions.node.split(".").map(Number); process.exit(a>20||(a===20&&b>=19)?0:1)'; then
    echo "throng: node $(node --version) is too old for the viewer's build (needs ≥ 20.19, e.g. NodeSource's nodejs): web/dist is not built"
    return 0
  fi
  if [ ! -d "$web/node_modules" ] || [ "$web/package-lock.json" -nt "$web/node_modules" ]; then
    echo "throng: installing the viewer's npm packages (npm ci in web/)"
    if ! (cd "$web" && npm ci --no-audit --no-fund); then
      echo "throng: npm ci failed in web/ (offline?): the browser viewer is not built; the rest goes on"
      return 0
    fi
    touch "$web/node_modules"
  fi
  echo "throng: building the browser viewer (web/dist)"
  (cd "$web" && npm run build --silent) || echo "throng: the browser viewer's build failed (see above); the rest goes on"
}
