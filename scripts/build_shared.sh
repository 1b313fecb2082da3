#!/usr/bin/env bash
# Build the fastcontact library as a shared object for C, Python (ctypes) and Fortran
# programs that link against it:   scripts/build_shared.sh [--examples]
#
#   build/libfastcontact.so      the library (every module of src/, bind(C) names fc_*)
#   build/shared/mod/*.mod       module files for Fortran programs (`use fc_legacy`)
#   build/legacy_sphere_f, build/legacy_sphere_c, build/legacy_f77, build/rolling_api   (with --examples) examples
#
# Sources are compiled in dependency order (worked out from `module`/`use` lines), with
# FC (default gfortran) and FFLAGS (default -O2).  Needs FFTW3, LAPACK and BLAS.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

FC=${FC:-gfortran}
CC=${CC:-gcc}
FFLAGS=${FFLAGS:--O2}
OUT=build/shared
mkdir -p "$OUT/obj" "$OUT/mod"
FFTW_INC=${FFTW_INC:-/usr/include}

# module provided by each file, and local modules each file uses
declare -A provides
sources=(src/*.f90 src/*.F90)
for f in "${sources[@]}"; do
    m=$(grep -iE '^[[:space:]]*module[[:space:]]+[a-z0-9_]+[[:space:]]*$' "$f" | head -1 | awk '{print tolower($2)}' || true)
    [ -n "$m" ] && provides[$m]=$f
done
deps_of() {
    grep -iE '^[[:space:]]*use[[:space:]]*(,[[:space:]]*(non_)?intrinsic[[:space:]]*::)?[[:space:]]*[a-z0-9_]+' "$1" \
        | grep -viE 'intrinsic' \
        | sed -E 's/^[[:space:]]*use[[:space:]]*(::)?[[:space:]]*([A-Za-z0-9_]+).*/\2/' | tr 'A-Z' 'a-z' | sort -u
}

declare -A done_file
objects=()
remaining=${#sources[@]}
while [ "$remaining" -gt 0 ]; do
    progress=0
    for f in "${sources[@]}"; do
        [ -n "${done_file[$f]:-}" ] && continue
        ready=1
        for d in $(deps_of "$f"); do
            src=${provides[$d]:-}
            if [ -n "$src" ] && [ "$src" != "$f" ] && [ -z "${done_file[$src]:-}" ]; then ready=0; break; fi
        done
        [ "$ready" -eq 1 ] || continue
        obj="$OUT/obj/$(basename "${f%.*}").o"
        echo "  $FC $FFLAGS -fPIC -c $f"
        $FC $FFLAGS -fPIC -I"$FFTW_INC" -J"$OUT/mod" -I"$OUT/mod" -c "$f" -o "$obj"
        objects+=("$obj")
        done_file[$f]=1
        remaining=$((remaining - 1))
        progress=1
    done
    if [ "$progress" -eq 0 ]; then
        echo "build_shared.sh: circular or missing module dependencies" >&2
        exit 1
    fi
done

$FC -shared -o build/libfastcontact.so "${objects[@]}" -lfftw3 -llapack -lblas
echo "built build/libfastcontact.so (modules in $OUT/mod)"

if [ "${1:-}" = "--examples" ]; then
    $FC $FFLAGS -I"$OUT/mod" example/legacy_sphere.f90 -o build/legacy_sphere_f \
        -Lbuild -lfastcontact -Wl,-rpath,"$PWD/build"
    $CC -O2 -Iinclude example/legacy_sphere.c -o build/legacy_sphere_c \
        -Lbuild -lfastcontact -Wl,-rpath,"$PWD/build" -lm
    $FC $FFLAGS -std=legacy example/legacy_f77.f -o build/legacy_f77 -Lbuild -lfastcontact -Wl,-rpath,"$PWD/build"
    $CC -O2 -Iinclude example/rolling_api.c -o build/rolling_api \
        -Lbuild -lfastcontact -Wl,-rpath,"$PWD/build" -lm
    echo "built build/legacy_sphere_f, build/legacy_sphere_c, build/legacy_f77 and build/rolling_api"
fi
