#!/usr/bin/env bash
# ctest capi_exports: libthrong.so exports exactly the functions throng.h declares with THRONG_API,
# nothing else (no C++ symbol of the libraries linked into it), and has its SONAME.
#   exports_test.sh LIBRARY HEADER
set -euo pipefail
lib="$1"
header="$2"
exported="$(nm -D --defined-only "$lib" | awk '{print $3}' | sort)"
# Declarations: "THRONG_API <return type> throng_<name>(" at the start of a line (comments and the
# macro's own definition do not start that way).
declared="$(grep -oE '^THRONG_API [^(]*\<throng_[a-z0-9_]+\(' "$header" | grep -oE 'throng_[a-z0-9_]+\($' | tr -d '(' | sort)"
[ -n "$declared" ] || { echo "FAIL: no THRONG_API functions found in $header"; exit 1; }
if [ "$exported" != "$declared" ]; then
  echo "FAIL: exported symbols differ from the header's THRONG_API functions"
  diff <(echo "$declared") <(echo "$exported") || true
  exit 1
fi
soname="$(objdump -p "$lib" | awk '/SONAME/ {print $2}')"
[[ "$soname" == libthrong.so.* ]] || { echo "FAIL: SONAME is '$soname', expected libthrong.so.<major>"; exit 1; }
echo "ok: $(echo "$exported" | wc -l) functions exported, all declared in throng.h; SONAME $soname"
