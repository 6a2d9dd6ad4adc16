#!/usr/bin/env bash
# Installs the Debian 12 packages throng needs that are missing (apt-get; sudo when not root).
# Sourced by scripts/demo.sh and scripts/test.sh; safe to run again (installs nothing when complete).
set -euo pipefail

THRONG_DEB_PACKAGES=(
  cmake ninja-build clang libclang-rt-14-dev g++ pkg-config
  librecast-dev nlohmann-json3-dev libcli11-dev libfmt-dev libtbb-dev libsqlite3-dev sqlite3
  libboost-dev librapidcheck-dev libgtest-dev libgmock-dev libbenchmark-dev
)

throng_install_deps() {
  local missing=()
  for p in "${THRONG_DEB_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
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
