#!/usr/bin/env bash
# Leak and memory-growth checks (doc/reliability.md):
#   1. valgrind memcheck of the driver on every example (grids shrunk to <= 16^2);
#   2. valgrind memcheck of a flat-API session (fastcontact-api-soak --calls 300: operator
#      rebuilds, tangential steps, handles created and finalised);
#   3. resident memory of 100000 flat-API calculations on one handle (release build):
#      growth after the first 10 % must stay below 2 MB.
# Fails when valgrind reports definitely or indirectly lost bytes (or possibly lost ones that
# are not libgomp's thread-local blocks) or the resident set grows.  "Still reachable" blocks
# (FFTW's planner tables, freed by nobody at exit) are listed, not counted.  Usage: scripts/leakcheck.sh [--calls N]
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
CALLS=100000
if [ "${1:-}" = "--calls" ]; then CALLS="$2"; fi
command -v valgrind >/dev/null || { echo "leakcheck: valgrind not installed"; exit 1; }
fpm build >/dev/null || exit 1
driver="$(fpm run fastcontact --runner echo 2>/dev/null | tail -n 1)"
soak="$(fpm run fastcontact-api-soak --runner echo 2>/dev/null | tail -n 1)"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
status=0
VG=(valgrind --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect)
summary() {   # name log
    local lost possible reach
    lost=$(grep -E 'definitely lost:|indirectly lost:' "$2" | awk '{gsub(",","",$4); s+=$4} END {print s+0}')
    possible=$(grep -E 'possibly lost:' "$2" | awk '{gsub(",","",$4); s+=$4} END {print s+0}')
    reach=$(grep 'still reachable:' "$2" | awk '{print $4" "$5" in "$7" blocks"}')
    printf 'leakcheck: %-34s lost %s bytes; possibly lost %s; still reachable %s\n' "$1" "$lost" "$possible" "${reach:-0}"
    if [ "$lost" != 0 ]; then
        status=1; grep -B2 -A20 'definitely lost in loss record\|indirectly lost in loss record' "$2" | head -n 60
    fi
    # "possibly lost" is listed, not counted: libgomp's worker threads keep their TLS blocks
    # (pthread_create -> _dl_allocate_tls) until exit, and valgrind sees them only sometimes
    if [ "$possible" != 0 ] && ! grep -A8 'possibly lost in loss record' "$2" | grep -q 'libgomp\|_dl_allocate_tls'; then
        status=1; grep -B2 -A20 'possibly lost in loss record' "$2" | head -n 60
    fi
}
for nml in example/*.nml; do
    sed -E 's/\b(nx|ny)( *= *)(1[7-9]|[2-9][0-9]|[0-9]{3,})\b/\1\216/g' "$nml" >"$tmp/case.nml"
    "${VG[@]}" "$driver" "$tmp/case.nml" --out "$tmp/out" >/dev/null 2>"$tmp/vg.log"
    summary "driver $(basename "$nml")" "$tmp/vg.log"
done
"${VG[@]}" "$soak" --calls 300 --no-rss >/dev/null 2>"$tmp/vg.log"
summary "flat API (300 calculations)" "$tmp/vg.log"
fpm run --profile release fastcontact-api-soak -- --calls "$CALLS" 2>/dev/null | tail -n 2 | tee "$tmp/soak.log"
grep -q 'api-soak: ok' "$tmp/soak.log" || status=1
if [ $status -eq 0 ]; then echo "leakcheck: clean"; else echo "leakcheck: FAILED"; fi
exit $status
