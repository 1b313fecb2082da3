#!/usr/bin/env bash
# Distributed BCCG vs the serial solver (doc/parallel.md): for each size and case, one serial
# run (saves the pressure) and distributed runs on 1 and 2 ranks (compare with it).
#   scripts/bench_dist.sh OUT.csv "512 1024 2048" "hertz rough"
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../mpi"
out="$(realpath -m "${1:-../doc/bench_parallel_dist.csv}")"
sizes="${2:-512 1024 2048}"
cases="${3:-hertz rough}"
command -v fpm >/dev/null || export PATH="$HOME/.venv-fpm/bin:$PATH"
FLAGS="-I/usr/include -fopenmp -O3 -funroll-loops"
FPM_FC=mpifort fpm build --flag "$FLAGS" --link-flag -fopenmp >/dev/null
bench="$(FPM_FC=mpifort fpm run --flag "$FLAGS" --link-flag -fopenmp fastcontact-mpi-bench --runner echo 2>/dev/null | tail -1)"
MPIRUN=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && MPIRUN+=(--allow-run-as-root)
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
echo "case,n,mode,ranks,threads,status,iterations,products,fn,setup_s,solve_s,peak_rss_mb_per_rank,dp_rel,dfn_rel,solve_cpu_s_max_rank,load1" >"$out"
for n in $sizes; do
    for c in $cases; do
        OMP_NUM_THREADS=1 "${MPIRUN[@]}" -np 1 "$bench" --n "$n" --case "$c" --serial --save "$tmp/p.bin" --csv "$out"
        for np in 1 2; do
            OMP_NUM_THREADS=1 "${MPIRUN[@]}" -np "$np" "$bench" --n "$n" --case "$c" --compare "$tmp/p.bin" --csv "$out"
        done
    done
done
cat "$out"
