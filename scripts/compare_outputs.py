#!/usr/bin/env python3
"""Compare two output trees of the batch driver (JSON summaries, CSV tables, reports' error
lines) numerically: every number must agree to a relative `--rtol` (default 1e-10, absolute
floor `--atol` 1e-300 scaled by the column's largest magnitude).  Timing keys (*seconds*) are
skipped; keys present on one side only are listed (new outputs), not counted as differences.

    python3 scripts/compare_outputs.py BEFORE_DIR AFTER_DIR [--rtol 1e-10]
Exit status 0 when every shared number agrees."""
import json, os, sys, csv, math, argparse

def walk(a, b, path, out, rtol):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if 'seconds' in k:
                continue
            if k not in a or k not in b:
                out['only'].add(path + '/' + k + (' (after only)' if k in b else ' (before only)'))
                continue
            walk(a[k], b[k], path + '/' + k, out, rtol)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out['diff'].append(f'{path}: length {len(a)} vs {len(b)}')
            return
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f'{path}[{i}]', out, rtol)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        out['numbers'] += 1
        if a != b:
            d = abs(a - b) / max(abs(a), abs(b))
            out['max_rel'] = max(out['max_rel'], d)
            if d > rtol:
                out['diff'].append(f'{path}: {a!r} vs {b!r} (rel {d:.2e})')
    elif a != b:
        if 'cpu' in str(a) or path.endswith('/message') and 'seconds' in str(a):
            return
        out['diff'].append(f'{path}: {a!r} vs {b!r}')

def compare_csv(pa, pb, out, rtol):
    ra = list(csv.reader(open(pa))); rb = list(csv.reader(open(pb)))
    if len(ra) != len(rb):
        out['diff'].append(f'{pb}: {len(ra)} vs {len(rb)} rows'); return
    if not ra:
        return
    ncol = len(ra[0])
    scale = [0.0] * ncol
    for row in ra[1:]:
        for j, v in enumerate(row):
            try: scale[j] = max(scale[j], abs(float(v)))
            except ValueError: pass
    header = ra[0]
    for i, (x, y) in enumerate(zip(ra, rb)):
        for j, (u, v) in enumerate(zip(x, y)):
            if j < len(header) and ('seconds' in header[j] or header[j] == 'seconds'):
                continue
            try:
                fu, fv = float(u), float(v)
            except ValueError:
                if u != v: out['diff'].append(f'{pb}:{i+1}:{j+1}: {u} vs {v}')
                continue
            out['numbers'] += 1
            if fu != fv:
                d = abs(fu - fv) / max(abs(fu), abs(fv), 1e-300)
                dcol = abs(fu - fv) / max(scale[j], 1e-300)   # relative to the column's largest value
                out['max_rel'] = max(out['max_rel'], min(d, dcol))
                if min(d, dcol) > rtol:
                    out['diff'].append(f'{pb}:{i+1}:{header[j] if j < len(header) else j}: {u} vs {v} (rel {d:.2e})')

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('before'); ap.add_argument('after'); ap.add_argument('--rtol', type=float, default=1e-10)
    o = ap.parse_args()
    out = {'diff': [], 'only': set(), 'numbers': 0, 'max_rel': 0.0}
    files = 0
    for root, _, names in os.walk(o.before):
        for n in sorted(names):
            pa = os.path.join(root, n); pb = os.path.join(o.after, os.path.relpath(pa, o.before))
            if not n.endswith(('.json', '.csv')):
                continue
            if not os.path.exists(pb):
                out['diff'].append(f'missing after: {pb}'); continue
            if n.endswith('.json'):
                files += 1
                walk(json.load(open(pa)), json.load(open(pb)), os.path.relpath(pb, o.after), out, o.rtol)
            elif n.endswith('.csv'):
                files += 1
                compare_csv(pa, pb, out, o.rtol)
    print(f'{files} files, {out["numbers"]} numbers compared, max relative difference {out["max_rel"]:.3e}, '
          f'{len(out["diff"])} differences above rtol = {o.rtol:g}')
    keys = sorted({p.split('/')[-1] for p in out['only']})
    if keys: print('keys on one side only:', ', '.join(keys))
    for d in out['diff'][:40]: print('  ', d)
    return 1 if out['diff'] else 0

if __name__ == '__main__':
    sys.exit(main())
