#!/usr/bin/env bash
# Leak and memory-growth checks (doc/reliability.md):
#   1. valgrind memcheck of the driver on every example (grids shrunk to <= 16^2);
#   2. valgrind memcheck of a flat-API session (fastcontact-api-soak --calls 300: operator
#      rebuilds, tangential steps, handles created and finalised);
#   3. resident memory of 100000 flat-API calculations on one handle (release build):
#      growth after the first 10 % must stay below 2 MB.
# Fails when valgrind reports definitely/indirectly/possibly lost bytes or the resident set
# grows.  "Still reachable" blocks (FFTW's planner tables, freed by nobody at exit) are
# listed, not counted.  Usage: scripts/leakcheck.sh [--calls N]
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
VG=(valgrind --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible)
summary() {   # name log
    local lost
    lost=$(grep -E 'definitely lost:|indirectly lost:|possibly lost:' "$2" | awk '{gsub(",","",$4); s+=$4} END {print s+0}')
    local reach
    reach=$(grep 'still reachable:' "$2" | awk '{print $4" "$5" in "$7" blocks"}')
    printf 'leakcheck: %-34s lost %s bytes; still reachable %s\n' "$1" "$lost" "${reach:-0}"
    if [ "$lost" != 0 ]; then
        status=1; grep -B2 -A20 'lost in loss record' "$2" | head -n 60
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
