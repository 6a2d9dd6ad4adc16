#!/usr/bin/env bash
# The README's first command: install what is missing (Debian and npm packages), build everything
# (Release) and the browser viewer, record the flagship demo (the museum) with a progress bar, then
# serve it live: open the printed URL to watch it, join as an avatar and guide a group (Ctrl-C stops).
#   scripts/demo.sh [--no-serve] [throng run flags...]
# --no-serve stops after the recording (for scripts); THRONG_DEMO_PORT picks the port (default 8080).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
serve=1
if [ "${1:-}" = "--no-serve" ]; then serve=0; shift; fi
source "$root/scripts/deps.sh"
throng_install_deps
throng_build "$root"
throng_build_web "$root"
mkdir -p "$root/out"
throng="$root/build/apps/throng/throng"
"$throng" run "$root/scenarios/museum.json" --out "$root/out/museum.sqlite" --force "$@"
echo
echo "Inspect it:    build/apps/throng/throng info out/museum.sqlite"
echo "Replay it:     build/apps/throng/throng serve out/museum.sqlite   (a timeline in the browser)"
echo "Picture:       /usr/bin/python3 scripts/plot_recording.py out/museum.sqlite   (needs python3-matplotlib)"
echo "Other scenes:  ls scenarios/   (for example build/apps/throng/throng serve scenarios/mall.json)"
if [ "$serve" = 0 ]; then
  echo "Live:          build/apps/throng/throng serve scenarios/museum.json   then open http://127.0.0.1:8080/"
  exit 0
fi
echo
echo "Now live: open the viewer URL below in a browser, join with a name, pick a group and guide it."
exec "$throng" serve "$root/scenarios/museum.json" --port "${THRONG_DEMO_PORT:-8080}"
