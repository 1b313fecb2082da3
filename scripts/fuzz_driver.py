#!/usr/bin/env python3
"""Seeded, time-bounded fuzz test of the fastcontact batch driver.

Mutates the example namelists (example/*.nml, grids shrunk to <= 16 elements per
direction so that one run takes well under a second) and runs the built driver on each
mutant as a child process with a wall-clock limit, a CPU-time limit and an address-space
limit (like `ulimit -v`).  Every run must end in one of

* exit 0  -- every case converged: JSON status "converged", no NaN/Inf in JSON or CSV;
* exit 2  -- an honest not_converged / diverged status in the JSON and on stderr;
* exit 1  -- a clean input error: a `fastcontact:` message on stderr that names the
             group and key (`&group key`), a syntax position (`group &g (line N)`), the
             case file, or a grid/limit;

and never in a signal, a timeout, a memory failure, gfortran runtime-error or backtrace
text, or NaN/Inf in the outputs.  A failure prints the seed, the mutation and the
reproducing namelist; the exit status is 1 when any run failed.

Usage:  scripts/fuzz_driver.py --driver PATH [--seed N] [--budget SECONDS]
            [--timeout SECONDS] [--mem-mb MB] [--max-runs N] [--keep DIR]

Standard library only (no venv needed).  The seed defaults to FUZZ_SEED or the clock and
is printed first: `--seed N` repeats a run exactly (same mutants in the same order).
"""
import argparse
import glob
import json
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

GROUP_KEYS = {
    'case': ['name', 'title', 'problem'],
    'material': ['g1', 'g2', 'nu1', 'nu2', 'ic_file'],
    'grid': ['nx', 'ny', 'xmin', 'xmax', 'ymin', 'ymax', 'auto', 'margin', 'n_across'],
    'geometry': ['kind', 'rx', 'ry', 'diameter', 'sigma', 'gamma', 'm_modes', 'n_modes', 'seed',
                 'amplitude', 'wavelength_x', 'wavelength_y', 'file', 'length'],
    'normal': ['approach', 'fn'],
    'tangential': ['mu', 'xi', 'eta', 'phi', 'fx', 'fy'],
    'solver': ['normal', 'tangential', 'tol', 'maxit', 'inner_maxit', 'inner_k', 'precondition',
               'precondition_tangential', 'deflation', 'cycle', 'omega', 'beta', 'smoother', 'strip',
               'target', 'target_pmax', 'max_levels', 'model'],
    'output': ['dir', 'table', 'table_format'],
}
# keys added since the table was written: the reader's own namelist statements are the
# authority (src/fc_input.f90), so a new key is fuzzed and named in messages at once
GROUP_KEYS['material'] += ['ic_file2']
GROUP_KEYS['grid'] += ['periodic']
GROUP_KEYS['tangential'] += ['mu_kinetic', 'dq', 'nsteps', 'sweep', 'sweep_from', 'sweep_to', 'sweep_n']
GROUP_KEYS['solver'] += ['rolling', 'threads']


def _reader_keys():
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'src', 'fc_input.f90')
    try:
        text = open(src).read()
    except OSError:
        return {}
    text = re.sub(r'&\s*\n\s*', ' ', text)
    found = {}
    for m in re.finditer(r'namelist\s*/(\w+)/\s*([\w ,]+)', text):
        found.setdefault(m.group(1).lower(), []).extend(k.strip().lower() for k in m.group(2).split(',') if k.strip())
    return found


for _g, _ks in _reader_keys().items():
    GROUP_KEYS.setdefault(_g, [])
    GROUP_KEYS[_g] += [k for k in _ks if k not in GROUP_KEYS[_g]]
INT_KEYS = {'nx', 'ny', 'n_across', 'm_modes', 'n_modes', 'seed', 'maxit', 'inner_maxit', 'inner_k',
            'max_levels', 'nsteps', 'sweep_n', 'threads'}
LOGICAL_KEYS = {'auto', 'precondition', 'precondition_tangential', 'deflation', 'target_pmax', 'table', 'periodic'}
STRING_KEYS = {'name', 'title', 'problem', 'ic_file', 'kind', 'file', 'normal', 'tangential', 'cycle',
               'smoother', 'strip', 'model', 'dir', 'ic_file2', 'sweep', 'rolling', 'table_format'}

BAD_REALS = ['NaN', 'Inf', '-Inf', 'Infinity', '-Infinity', '1e308', '-1e308', '1e300', '1e-300', '-1e-300',
             '0', '-0.0', '-1', '1e', '1.0.0', '1e+', '.', '+', '--1', '1d400', '2147483648', "'text'",
             '.true.', '3*1.0', '1,2', '()', '0x10', '1e30', '-1e30', '4.9e-324', '1.7976931348623157e308']
BAD_INTS = ['0', '-1', '-2147483648', '2147483647', '2147483648', '99999999999', '16777217',
            '4097', '1.5', 'NaN', '1e9', "'a'", '.false.', '3*2', '', '-0', '+7', '1 2']
BAD_LOGICALS = ['1', "'yes'", '.maybe.', 'T', 'F', '.t.', 'NaN', '']
BAD_STRINGS = ["''", "'x'", "'" + 'a' * 70 + "'", "'" + 'b' * 200 + "'", "'" + 'c' * 5000 + "'",
               "'../../etc'", "'a b'", "'V(2147483647,1)'", "'V(1,2147483647)'", "'V(-1,1)'", "'V(0,0)'",
               "'V(99999999999,1)'", "'V(1000,1000)'", "'W(1,1)'", "'V(1,1'", "'fmg'", "'norm'", "'bccg'",
               "'tangential'", "'normal+tangential'", "'hertz'", "'strip_mp1'", "'punch_rough'", "'wavy'",
               "'table'", "'cylinder'", "'strip2d'", "'/dev/null'", "'convexgs'", "'fft-rsm'", "'jacobi'",
               "'full'", '12', 'unquoted', "'unterminated", '"dq"']
# values that stay meaningful: exercise real solver paths, not only the validator
GOOD_VALUES = {
    'nx': ['1', '2', '3', '8', '16', '17'], 'ny': ['1', '2', '8', '16'],
    'maxit': ['1', '2', '5', '1000000', '1000001'], 'tol': ['1e-300', '1e-14', '0.5', '0.99', '1e-3'],
    'inner_maxit': ['1', '3'], 'inner_k': ['1', '50'], 'n_modes': ['1', '16777217', '100000'],
    'm_modes': ['1', '16777217', '100000'], 'approach': ['1e-9', '10', '-5', '1e6'],
    'fn': ['1e-12', '1e300', '1e30', '1'], 'mu': ['0', '1e-9', '1e9'], 'omega': ['1.99', '1e-9'],
    'beta': ['0', '1e9'], 'target': ['1e-300', '0.5', '1e-6'], 'max_levels': ['2', '12', '13'],
    'sigma': ['0', '1e9'], 'gamma': ['1e-9', '1'], 'diameter': ['1e-9', '1e9'],
    'rx': ['1e-9', '1e12'], 'ry': ['0', '1e12'], 'margin': ['0', '10'], 'n_across': ['4096', '4097'],
    'xmax': ['1e308', 'Infinity', '1e-300'], 'ymax': ['Infinity', '1e308'], 'xmin': ['-1e308'],
    'g1': ['1e29', '1e-300'], 'g2': ['1e29', '1e300'], 'nu1': ['0.4999999', '0.5'], 'nu2': ['0', '-0.1'],
    'phi': ['1e9', '1e-12'], 'xi': ['1e9', '-1e9'], 'fx': ['1e300'], 'length': ['1e-9', '1e9'],
    'amplitude': ['1e9'], 'wavelength_x': ['1e-9'], 'seed': ['-1', '2147483647'],
}

FORBIDDEN = [re.compile(p, re.I) for p in (
    r'Fortran runtime error', r'Backtrace', r'Program received signal', r'runtime error',
    r'Error termination', r'Operating system error', r'^At line \d+ of file', r'Segmentation',
    r'AddressSanitizer', r'LeakSanitizer', r'Out of memory', r'Cannot allocate', r'Allocation would exceed',
    r'floating point exception', r'SIGFPE', r'SIGSEGV', r'core dumped', r'ERROR STOP')]
NONFINITE = re.compile(r'(?<![A-Za-z_])([+-]?nan|[+-]?inf(inity)?)(?![A-Za-z_])', re.I)
# a clean input error names where: '&group' and a key ('key = value', 'key:', "unknown key 'k'"),
# a syntax position ('group &g (line N)'), the case file, or the limit of a count
GROUP_RE = '|'.join(GROUP_KEYS)
KEY_RE = '|'.join(sorted({k for ks in GROUP_KEYS.values() for k in ks}, key=len, reverse=True))
NAMED_ERROR = re.compile(
    r'&(' + GROUP_RE + r')\b.*?\b(' + KEY_RE + r')\b\s*(=|:|,|\(|\bmust\b)'
    r"|&(" + GROUP_RE + r")\b.*unknown key '"
    r'|group &\w+ \(line \d+\)'
    r'|unknown group &\w+'
    r'|case file'
    r'|no namelist groups'
    r"|'&' not followed by a group name", re.I)


def shrink(text):
    """Example cases on tiny grids: every nx/ny > 16 becomes 16 (powers of 2 stay powers of 2);
    creep-force sweeps of at most 4 points and transient runs of at most 8 steps, so that a
    mutation that enlarges the grid (nx = 4097) multiplies a few solves, not a hundred (the
    20-point curves of rolling_curves.nml at 4097 x 16: 10 s of the run's 20)."""
    def sub(limit):
        def f(m):
            v = int(m.group(2))
            return m.group(1) + (str(limit) if v > limit else m.group(2))
        return f
    text = re.sub(r'(\b(?:nx|ny)\s*=\s*)(\d+)', sub(16), text, flags=re.I)
    text = re.sub(r'(\bsweep_n\s*=\s*)(\d+)', sub(4), text, flags=re.I)
    return re.sub(r'(\bnsteps\s*=\s*)(\d+)', sub(8), text, flags=re.I)


def load_corpus():
    corpus = []
    for path in sorted(glob.glob(os.path.join(ROOT, 'example', '*.nml'))):
        with open(path) as f:
            text = shrink(f.read())
        # one file per case chunk as well, so that one mutation is not masked by case 1
        corpus.append((os.path.basename(path), text))
    return corpus


def items(text):
    """(start, end, group, key) of every `key = value` value span in the text."""
    out = []
    for g in re.finditer(r'&(\w+)([^/]*)/', text, re.S):
        group = g.group(1).lower()
        body_start = g.start(2)
        for kv in re.finditer(r"(\w+)\s*=\s*('[^']*'|\"[^\"]*\"|[^,/'\"]*?)\s*(?=,|\n|$|\s+\w+\s*=)", g.group(2)):
            out.append((body_start + kv.start(2), body_start + kv.end(2), group, kv.group(1).lower()))
    return out


def mutate(text, rng):
    """Return (mutant, description, group, key) -- key None for structural mutations."""
    its = items(text)
    r = rng.random()
    if its and r < 0.55:
        s, e, group, key = rng.choice(its)
        if rng.random() < 0.35 and key in GOOD_VALUES:
            val = rng.choice(GOOD_VALUES[key])
        elif key in INT_KEYS:
            val = rng.choice(BAD_INTS + BAD_REALS[:6])
        elif key in LOGICAL_KEYS:
            val = rng.choice(BAD_LOGICALS)
        elif key in STRING_KEYS:
            val = rng.choice(BAD_STRINGS)
        else:
            val = rng.choice(BAD_REALS)
        return text[:s] + val + text[e:], f'&{group} {key} = {val[:80]}', group, key
    if its and r < 0.62:                       # insert a valid-looking key with a bad value
        s, e, group, key = rng.choice(its)
        other = rng.choice(GROUP_KEYS.get(group, ['x']))
        val = rng.choice(BAD_REALS + BAD_INTS + BAD_STRINGS)
        ins = f', {other} = {val}'
        return text[:e] + ins + text[e:], f'&{group} add {other} = {val[:80]}', group, other
    if its and r < 0.66:                       # unknown key
        s, e, group, key = rng.choice(its)
        return text[:e] + ', bogus_key = 1' + text[e:], f'&{group} unknown key', group, 'bogus_key'
    if its and r < 0.70:                       # delete a key (missing required value)
        s, e, group, key = rng.choice(its)
        ks = text.rfind(key, 0, s)
        if ks < 0:
            ks = s
        return text[:ks] + text[e:], f'&{group} delete {key}', group, key
    r2 = rng.random()
    if r2 < 0.15:                              # missing '/'
        slashes = [m.start() for m in re.finditer(r'/\s*$', text, re.M)]
        if slashes:
            p = rng.choice(slashes)
            return text[:p] + text[p + 1:], "drop a '/'", None, None
    if r2 < 0.30:                              # truncation
        p = rng.randrange(1, max(2, len(text)))
        return text[:p], f'truncate at byte {p}', None, None
    if r2 < 0.40:                              # long line
        n = rng.choice([4079, 4090, 5000, 20000])
        line = '&case title = \'' + 'x' * n + '\' /\n' if rng.random() < 0.5 else ' ' * n + '&grid nx = 8 /\n'
        return text + line, f'long line ({n} chars)', None, None
    if r2 < 0.50:                              # unknown group
        return text + '\n&bogus x = 1 /\n', 'unknown group', None, None
    if r2 < 0.60:                              # many cases
        n = rng.choice([30, 10001])            # a few cheap cases, or over the case limit
        # over the limit the file is refused as a whole; but stacked byte flips can merge
        # cases and bring the count below it, and thousands of inherited solves (4400
        # periodic friction cells of rough_cell_friction.nml: 20 s) would then exceed the
        # run's time limit with a correct driver.  So those cases are analytic Hertz ones
        # (or, where the scene is not quadratic, input errors): microseconds each.
        kind = '' if n < 10000 else ", problem = 'hertz'"
        extra = ''.join(f"&case name = 'c{i}'{kind} /\n" for i in range(n))
        return text + extra, f'{n} extra cases', None, None
    if r2 < 0.70:                              # random byte flips
        b = bytearray(text.encode())
        for _ in range(rng.randint(1, 5)):
            if b:
                b[rng.randrange(len(b))] = rng.choice(b"&/=',\"!()*$0123456789.eE+-\n\t\x00\xff")
        return b.decode('latin-1'), 'byte flips', None, None
    if r2 < 0.78:                              # duplicate a group
        gs = list(re.finditer(r'&\w+[^/]*/', text, re.S))
        if gs:
            g = rng.choice(gs)
            return text[:g.end()] + '\n' + g.group(0) + text[g.end():], 'duplicate group', None, None
    if r2 < 0.86:                              # empty / whitespace / binary file
        return rng.choice(['', '\n\n', '/', '&', '&case', '\x00\x01\x02', '&end', '$case name=\'a\' $end']), \
            'degenerate file', None, None
    # two mutations stacked
    t1, d1, g1, k1 = mutate(text, rng)
    t2, d2, g2, k2 = mutate(t1, rng)
    return t2, d1 + ' + ' + d2, g2 or g1, k2 or k1


def limit(mem_mb, cpu_s):
    def f():
        if mem_mb > 0:                 # 0: no address-space limit (AddressSanitizer builds)
            resource.setrlimit(resource.RLIMIT_AS, (mem_mb * 2**20, mem_mb * 2**20))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s + 1))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        os.setsid()
    return f


def check_outputs(outdir, rc):
    """Problems with the JSON/CSV outputs of a finished run."""
    problems = []
    statuses = []
    for path in glob.glob(os.path.join(outdir, '*.json')):
        with open(path, errors='replace') as f:
            txt = f.read()
        bad = []

        def constant(name):          # NaN, Infinity, -Infinity as JSON numbers
            bad.append(name)
            return float('nan')
        try:
            data = json.loads(txt, parse_constant=constant)
            statuses.append(data.get('status'))
        except ValueError as exc:
            problems.append(f'{os.path.basename(path)}: invalid JSON ({exc})')
        if bad:
            problems.append(f'{os.path.basename(path)}: non-finite number {bad[0]} in JSON')
    for path in glob.glob(os.path.join(outdir, '*.csv')):
        with open(path, errors='replace') as f:
            for ln, line in enumerate(f, 1):
                if ln == 1:
                    continue
                m = NONFINITE.search(line)
                if m:
                    problems.append(f'{os.path.basename(path)} line {ln}: non-finite value {m.group(0)!r}')
                    break
    ok = {'converged', 'not_converged', 'diverged', 'error', 'analytic'}
    for st in statuses:
        if st not in ok:
            problems.append(f'unknown JSON status {st!r}')
    if rc == 0 and any(st in ('not_converged', 'diverged', 'error') for st in statuses):
        problems.append(f'exit 0 but a JSON status is {statuses}')
    if rc == 2 and not any(st in ('not_converged', 'diverged') for st in statuses):
        problems.append(f'exit 2 but no JSON reports not_converged/diverged ({statuses})')
    return problems


def run_one(driver, text, workdir, timeout, mem_mb):
    case = os.path.join(workdir, 'case.nml')
    out = os.path.join(workdir, 'out')
    shutil.rmtree(out, ignore_errors=True)
    with open(case, 'w', encoding='latin-1', errors='replace') as f:
        f.write(text)
    t0 = time.monotonic()
    try:
        p = subprocess.run([driver, case, '--out', out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           stdin=subprocess.DEVNULL, timeout=timeout, cwd=workdir,
                           preexec_fn=limit(mem_mb, int(timeout) + 1))
    except subprocess.TimeoutExpired as exc:
        return None, '', f'time limit {timeout} s exceeded', time.monotonic() - t0
    dt = time.monotonic() - t0
    so = p.stdout.decode('utf-8', 'replace')
    se = p.stderr.decode('utf-8', 'replace')
    return p.returncode, so + se, se, dt


def classify(rc, output, stderr, outdir, key):
    problems = []
    if rc is None:
        return [stderr]
    if rc < 0:
        problems.append(f'killed by signal {-rc} ({signal.Signals(-rc).name})')
    elif rc not in (0, 1, 2):
        problems.append(f'exit status {rc} (expected 0, 1 or 2)')
    for pat in FORBIDDEN:
        m = pat.search(output)
        if m:
            problems.append(f'forbidden text {m.group(0)!r} in the output')
    if rc in (0, 2):
        problems += check_outputs(outdir, rc)
    if rc == 1:
        errs = [l for l in stderr.splitlines() if l.startswith('fastcontact:') and 'case(s):' not in l]
        if not errs:
            problems.append('exit 1 without a fastcontact: error message on stderr')
        for line in errs:
            if 'namelist read failed' in line or not (NAMED_ERROR.search(line) or 'solver ' in line):
                problems.append(f'error message names no key and value: {line.strip()[:300]}')
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--driver', required=True)
    ap.add_argument('--seed', type=int, default=int(os.environ.get('FUZZ_SEED', time.time_ns() % 2**31)))
    ap.add_argument('--budget', type=float, default=90.0, help='total seconds (default 90)')
    ap.add_argument('--timeout', type=float, default=20.0, help='per-run wall-clock limit (default 20 s)')
    ap.add_argument('--mem-mb', type=int, default=2048, help='per-run address-space limit (default 2048 MB)')
    ap.add_argument('--max-runs', type=int, default=100000)
    ap.add_argument('--keep', help='directory to keep the failing namelists in')
    args = ap.parse_args()
    driver = os.path.abspath(args.driver)
    print(f'fuzz_driver: seed {args.seed} (repeat: scripts/fuzz_driver.py --driver {args.driver} '
          f'--seed {args.seed} --budget {args.budget:g}), per-run limits {args.timeout:g} s, {args.mem_mb} MB')
    rng = random.Random(args.seed)
    corpus = load_corpus()
    if not corpus:
        print('fuzz_driver: no example/*.nml found', file=sys.stderr)
        return 1
    tmp = tempfile.mkdtemp(prefix='fcfuzz')
    t_end = time.monotonic() + args.budget
    counts = {0: 0, 1: 0, 2: 0}
    failures = []
    nrun = 0
    slowest = (0.0, '')
    try:
        # the unmutated corpus first: every example must pass as it is
        queue = [(name, text, 'unmutated', None, None) for name, text in corpus]
        while nrun < args.max_runs and time.monotonic() < t_end:
            if queue:
                name, text, desc, group, key = queue.pop(0)
            else:
                name, base = rng.choice(corpus)
                text, desc, group, key = mutate(base, rng)
            rc, output, stderr, dt = run_one(driver, text, tmp, args.timeout, args.mem_mb)
            nrun += 1
            if dt > slowest[0]:
                slowest = (dt, f'{name}: {desc}')
            problems = classify(rc, output, stderr, os.path.join(tmp, 'out'), key)
            if rc in counts:
                counts[rc] += 1
            if problems:
                failures.append((name, desc, text, problems, rc))
                print(f'\nFUZZ FAILURE #{len(failures)} (run {nrun}, from {name}, mutation: {desc}, exit {rc}, '
                      f'{dt:.2f} s)')
                for pr in problems:
                    print('  - ' + pr)
                print('  reproducing namelist (between the markers):\n----8<----')
                print(text if len(text) < 6000 else text[:3000] + '\n...[%d chars]...\n' % len(text) + text[-2000:])
                print('---->8----')
                tail = '\n'.join(output.strip().splitlines()[-6:])
                print('  last output lines:\n    ' + tail.replace('\n', '\n    '))
                if args.keep:
                    os.makedirs(args.keep, exist_ok=True)
                    with open(os.path.join(args.keep, f'fail_{len(failures):03d}.nml'), 'w',
                              encoding='latin-1', errors='replace') as f:
                        f.write(text)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f'\nfuzz_driver: seed {args.seed}: {nrun} runs, exit 0: {counts[0]}, exit 1 (input error): {counts[1]}, '
          f'exit 2 (not converged): {counts[2]}, failures: {len(failures)}; slowest run {slowest[0]:.2f} s '
          f'({slowest[1][:100]})')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
