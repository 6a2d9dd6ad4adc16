#!/usr/bin/env bash
# The README's first command: install what is missing, build everything (Release), run the
# flagship demo scenario with a progress bar, and say where the recording went.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/deps.sh"
throng_install_deps
throng_build "$root"
throng_build_web "$root"
mkdir -p "$root/out"
"$root/build/apps/throng/throng" run "$root/scenarios/museum.json" --out "$root/out/museum.sqlite" --force "$@"
echo
echo "Inspect it:    build/apps/throng/throng info out/museum.sqlite"
echo "Picture:       /usr/bin/python3 scripts/plot_recording.py out/museum.sqlite   (needs python3-matplotlib)"
echo "Other scenes:  ls scenarios/   (for example build/apps/throng/throng run scenarios/plaza.json)"
echo
echo "Watch it live, join and guide a group in the browser:"
echo "  build/apps/throng/throng serve scenarios/museum.json"
echo "  then open http://127.0.0.1:8080/"
