#!/usr/bin/env bash
# Layer of every library module (src/): 1 for a module that uses no other library module,
# else 1 + the highest layer among the library modules it uses.  Prints "layer module",
# lowest first, and the depth of the graph:   scripts/module_layers.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
declare -A uses layer
for f in src/*.f90; do
    m=$(grep -iE '^[[:space:]]*module[[:space:]]+[a-z0-9_]+[[:space:]]*$' "$f" | head -1 | awk '{print tolower($2)}')
    [ -n "$m" ] || continue
    uses[$m]=$(grep -iE '^[[:space:]]*use[[:space:]]+[a-z0-9_]+' "$f" | grep -viE 'intrinsic' \
        | sed -E 's/^[[:space:]]*use[[:space:]]+([A-Za-z0-9_]+).*/\1/' | tr 'A-Z' 'a-z' | sort -u | tr '\n' ' ' || true)
done
depth_of() {
    local m=$1 d=1 u l
    if [ -n "${layer[$m]:-}" ]; then echo "${layer[$m]}"; return; fi
    for u in ${uses[$m]}; do
        [ "$u" = "$m" ] && continue
        [ -n "${uses[$u]+x}" ] || continue
        l=$(depth_of "$u")
        [ "$l" -ge "$d" ] && d=$((l + 1))
    done
    echo "$d"
}
for m in "${!uses[@]}"; do layer[$m]=$(depth_of "$m"); done
for m in "${!layer[@]}"; do echo "${layer[$m]} $m"; done | sort -n -k1,1 -k2,2
echo "depth: $(for m in "${!layer[@]}"; do echo "${layer[$m]}"; done | sort -n | tail -1)"
