#!/usr/bin/env bash
# MPI batch vs serial driver (doc/parallel.md): 40 cases (20 Cattaneo creep-sweep cases on
# 120 x 100, 20 Hertz approach-sweep cases on 128 x 128), serial `fastcontact` and
# `mpirun -np 2 fastcontact-mpi`, alternating, REPEATS times; wall and CPU seconds.
# With BATCH_GRIDS=large the same 40 cases on the thesis' grids (Cattaneo 240 x 200, Hertz
# 256 x 256): about 5x the work, so the fixed start-up of mpirun and MPI_Init (~0.35 s wall
# here) weighs less.
#   [BATCH_GRIDS=large] scripts/bench_batch.sh [OUT.csv] [REPEATS]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
command -v fpm >/dev/null || export PATH="$HOME/.venv-fpm/bin:$PATH"
out="$(realpath -m "${1:-doc/bench_parallel_batch.csv}")"
repeats="${2:-3}"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
nml="$tmp/batch40.nml"
if [ "${BATCH_GRIDS:-small}" = large ]; then cnx=240; cny=200; hn=256; else cnx=120; cny=100; hn=128; fi
{
    echo "&case name = 'cat_01', problem = 'normal+tangential' /"
    echo "&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /"
    echo "&grid nx = $cnx, ny = $cny, xmin = -1.2857, xmax = 1.2857, ymin = -1.2857, ymax = 1.2857 /"
    echo "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /"
    echo "&normal fn = 9.1954 /"
    echo "&tangential mu = 0.4, xi = 1.0e-4, eta = 0.0, phi = 0.0 /"
    echo "&solver tol = 1.0e-5, maxit = 1000 /"
    for i in $(seq 2 20); do
        printf "&case name = 'cat_%02d' /\n&tangential xi = %s /\n" "$i" "$(awk "BEGIN{print 1.0e-4*$i}")"
    done
    echo "&case name = 'hz_01', problem = 'normal' /"
    echo "&material g1 = 82000.0, g2 = 82000.0, nu1 = 0.28, nu2 = 0.28 /"
    echo "&grid nx = $hn, ny = $hn, xmin = -10.0, xmax = 10.0, ymin = -6.0, ymax = 6.0 /"
    echo "&geometry kind = 'quadratic', rx = 300.0, ry = 163.0 /"
    echo "&normal approach = 0.05 /"
    echo "&solver tol = 1.0e-8 /"
    for i in $(seq 2 20); do
        printf "&case name = 'hz_%02d' /\n&normal approach = %s /\n" "$i" "$(awk "BEGIN{print 0.05+0.005*$i}")"
    done
} >"$nml"
fpm build --profile release >/dev/null
serial="$(fpm run --profile release fastcontact --runner echo 2>/dev/null | tail -1)"
FLAGS="-I/usr/include -fopenmp -O3 -funroll-loops"
( cd mpi && FPM_FC=mpifort fpm build --flag "$FLAGS" --link-flag "-fopenmp" >/dev/null )
mpibin="mpi/$(cd mpi && FPM_FC=mpifort fpm run --flag "$FLAGS" --link-flag "-fopenmp" fastcontact-mpi --runner echo 2>/dev/null | tail -1)"
MPIRUN=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && MPIRUN+=(--allow-run-as-root)
# cpu_max_rank_s: the largest CPU time of one rank (each rank timed by /usr/bin/time), i.e. the
# wall time on an idle machine with one core per rank; serial CPU / cpu_max_rank is the
# speed-up the batch achieves when each rank has its core (load balance and overheads included).
echo "run,mode,ranks,wall_s,cpu_s,cpu_max_rank_s,load1,exit" >"$out"
for r in $(seq 1 "$repeats"); do
    for mode in serial mpi2 mpi2_ob1; do
        rm -rf "$tmp/out"
        if [ "$mode" = serial ]; then
            cmd=(env OMP_NUM_THREADS=1 "$serial" "$nml" --out "$tmp/out"); ranks=1
        else
            opts=(); [ "$mode" = mpi2_ob1 ] && opts=(--mca pml ob1)
            cmd=(env OMP_NUM_THREADS=1 "${MPIRUN[@]}" "${opts[@]}" -np 2 sh -c \
                '/usr/bin/time -f "%U %S" -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' "$tmp/rank" "$mpibin" "$nml" --out "$tmp/out"); ranks=2
        fi
        set +e
        /usr/bin/time -f "%e %U %S" -o "$tmp/time" "${cmd[@]}" >"$tmp/log" 2>&1
        code=$?
        set -e
        read -r wall user sys <"$tmp/time"
        cpu="$(awk "BEGIN{print $user+$sys}")"
        cmax="$cpu"
        if [ "$mode" != serial ]; then
            cmax="$(cat "$tmp"/rank.* | awk '{c=$1+$2; if (c>m) m=c} END{print m}')"
            rm -f "$tmp"/rank.*
        fi
        echo "$r,$mode,$ranks,$wall,$cpu,$cmax,$(cut -d' ' -f1 /proc/loadavg),$code" | tee -a "$out"
    done
done
