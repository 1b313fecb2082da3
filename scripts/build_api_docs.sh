#!/usr/bin/env bash
# Build the API reference of fastcontact with FORD (from PyPI, in a virtual environment)
# into build/api-doc/ (not committed; `build/` is ignored).  Exits non-zero when FORD fails
# or reports an error; warnings (e.g. a [[link]] to an unknown entity) are listed, and are
# fatal too with FORD_STRICT=1.
#
#   scripts/build_api_docs.sh            # creates the venv on first use (~40 s), then ~20 s
#   FORD_VENV=/path FORD_STRICT=1 scripts/build_api_docs.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

FORD_VERSION=7.0.13
venv="${FORD_VENV:-${HOME}/.cache/fastcontact-ford-venv}"

if ! "$venv/bin/ford" --version 2>/dev/null | grep -q "$FORD_VERSION"; then
    echo "installing FORD $FORD_VERSION into $venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install --no-input --disable-pip-version-check --quiet "ford==$FORD_VERSION" </dev/null
fi
mkdir -p build
log=build/ford.log
start=$(date +%s)
set +e
"$venv/bin/ford" ford.md >"$log" 2>&1
rc=$?
set -e
grep -v '━' "$log" || true     # progress bars off
echo "FORD finished in $(( $(date +%s) - start )) s (exit status $rc)"
[ "$rc" -eq 0 ] || { echo "FORD failed (exit status $rc)" >&2; exit 1; }
if grep -Eqi '^ *(error|critical)' "$log"; then
    echo "FORD reported errors (see above)" >&2
    exit 1
fi
nwarn=$(grep -ci '^ *warning' "$log" || true)
echo "FORD warnings: $nwarn"
if [ "${FORD_STRICT:-0}" = 1 ] && [ "$nwarn" -gt 0 ]; then
    echo "FORD_STRICT=1: warnings are fatal" >&2
    exit 1
fi
[ -f build/api-doc/index.html ] || { echo "build/api-doc/index.html was not written" >&2; exit 1; }
echo "API reference: build/api-doc/index.html"
