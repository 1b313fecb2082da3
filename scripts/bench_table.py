#!/usr/bin/env python3
"""Print the fastcontact-bench CSV (default doc/bench_normal.csv) as a Markdown table."""
import csv
import sys

path = sys.argv[1] if len(sys.argv) > 1 else "doc/bench_normal.csv"
rows = list(csv.DictReader(open(path, newline="")))
print("| solver | grid | unknowns | RMS error vs Hertz [N/mm²] | F error (rel.) | iterations | matvecs "
      "| residual | status | set-up [s] | solve [s] | total [s] |")
print("|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|")
for r in rows:
    print(f"| {r['solver'].upper()} | {r['nx']}² | {int(r['unknowns']):,} | {float(r['error_rms']):.3f} "
          f"| {float(r['fn_error_rel']):+.1e} | {r['iterations']} | {r['matvecs']} "
          f"| {float(r['residual']):.1e} | {r['status']} | {float(r['setup_seconds']):.3f} "
          f"| {float(r['solve_seconds']):.3f} | {float(r['total_seconds']):.3f} |")
