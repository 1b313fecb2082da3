#!/usr/bin/env bash
# Serial performance before/after (doc/parallel.md): builds REF (default: the merge base
# with main) in a temporary directory and the working tree, both --profile release, and runs
# alternately REPEATS times, one thread (OMP_NUM_THREADS=1):
#   fastcontact-bench --solver bccg --max 1024     (Hertz Test I, set-up and solve seconds)
#   fastcontact example/cattaneo.nml               (8 Cattaneo cases, whole-process CPU)
#   scripts/bench_serial_compare.sh [OUT.csv] [REPEATS] [REF]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
command -v fpm >/dev/null || export PATH="$HOME/.venv-fpm/bin:$PATH"
out="$(realpath -m "${1:-doc/bench_parallel_serial.csv}")"
repeats="${2:-3}"
ref="${3:-$(git merge-base HEAD main)}"
base="$(mktemp -d)"; tmp="$(mktemp -d)"; trap 'rm -rf "$base" "$tmp"' EXIT
git archive "$ref" | tar -x -C "$base"
(cd "$base" && fpm build --profile release >/dev/null)
fpm build --profile release >/dev/null
bin_before="$base/$(cd "$base" && fpm run --profile release fastcontact-bench --runner echo 2>/dev/null | tail -1)"
drv_before="$base/$(cd "$base" && fpm run --profile release fastcontact --runner echo 2>/dev/null | tail -1)"
bin_after="$PWD/$(fpm run --profile release fastcontact-bench --runner echo 2>/dev/null | tail -1)"
drv_after="$PWD/$(fpm run --profile release fastcontact --runner echo 2>/dev/null | tail -1)"
echo "version,repeat,case,nx,setup_s,solve_s,total_s,cpu_s,load1" >"$out"
export OMP_NUM_THREADS=1
for r in $(seq 1 "$repeats"); do
    for v in before after; do
        if [ "$v" = before ]; then b="$bin_before"; d="$drv_before"; else b="$bin_after"; d="$drv_after"; fi
        load="$(cut -d' ' -f1 /proc/loadavg)"
        "$b" --solver bccg --max 1024 --out "$tmp/b.csv" >/dev/null
        # setup_seconds, solve_seconds, total_seconds are columns 15-17
        awk -F, -v v="$v" -v r="$r" -v l="$load" 'NR>1 {print v","r",hertz_bccg,"$3","$15","$16","$17",,"l}' "$tmp/b.csv" >>"$out"
        /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$d" example/cattaneo.nml --out "$tmp/o" >/dev/null
        read -r wall user sys <"$tmp/t"
        echo "$v,$r,cattaneo_example,60,,,$wall,$(awk "BEGIN{print $user+$sys}"),$load" >>"$out"
    done
done
cat "$out"
