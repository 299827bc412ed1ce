#!/usr/bin/python3
"""Is calibrate's 1σ honest at each rate, and what does joining two streams
cost? Monte Carlo over seeds against the simulator's truth
(docs/validation.md, "Two streams at two rates").

For each seed, one session is simulated at 2000 Hz with its truth (`mpcal
simulate static --preset mti-g --gyro --positions 12 --dwell 5 --turn 1.5
--rest 3 --noise-density 0.0005 --truth`), and for each pair of rates
tests/data/streams/make_streams.py (Python, apart from mpcal's reader and
resampler) splits it into an accelerometer stream and a gyroscope stream at
their own jittered stamps, and into the single-stream logs at either stream's
stamps. Each of the three is calibrated and scored parameter by parameter:

  z = (estimate - truth) / the file's own 1σ

over the accelerometer's nine parameters (accel), the gyroscope's M (m) and
bias (b). An honest 1σ gives RMS z within 0.8-1.25 and a mean z near 0
(±2/√n). Two more columns compare files with each other:

  single@a - single@g, by the 1σ of single@g alone, and by √(σa² + σg²): the
    two single streams are two noise realisations (different rows of the
    dense session), so their difference has the spread of both 1σ combined;
  two - single@g (gyroscope): the same gyroscope samples, so what is left is
    what the joining does (and the accelerometer's directions of the turns).

  /usr/bin/python3 bench/streams_mc.py BUILD/mpcal [--seeds 1-40]
      [--rates 63/200,250/400] [--jobs 2]
"""
import argparse
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MAKE_STREAMS = os.path.join(HERE, '..', 'tests', 'data', 'streams', 'make_streams.py')
ACCEL = ('bias_mps2', 'scale_factor_error', 'non_orthogonality_rad')


def params(cal):
    """(group, name, value, sigma) for every parameter of a calibration."""
    def entries(block, name):
        values = block[name]
        keys = sorted(values) if isinstance(values, dict) else range(len(values))
        std = block.get('std', {}).get(name)
        for k in keys:
            yield '%s[%s]' % (name, k), values[k], std[k] if std is not None else float('nan')

    out = [('accel', n, v, s) for name in ACCEL for n, v, s in entries(cal, name)]
    g = cal.get('gyroscope')
    if g:
        for group, name in (('m', 'm'), ('b', 'bias_radps')):
            out += [(group, n, v, s) for n, v, s in entries(g, name)]
    return out


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def one_seed(mpcal, seed, rates, workdir):
    w = os.path.join(workdir, 's%d' % seed)
    os.makedirs(w, exist_ok=True)
    dense, truth_path = os.path.join(w, 'dense.csv'), os.path.join(w, 'truth.json')
    r = run([mpcal, 'simulate', 'static', '--preset', 'mti-g', '--gyro', '--seed', str(seed),
             '--positions', '12', '--dwell', '5', '--turn', '1.5', '--rest', '3',
             '--rate', '2000', '--noise-density', '0.0005', '--digits', '9',
             '-o', dense, '--truth', truth_path])
    if r.returncode != 0:
        sys.exit('simulate failed: ' + r.stderr)
    with open(truth_path) as f:
        truth = params(json.load(f))
    results = {}
    for pair in rates:
        ar, gr = pair.split('/')
        s = os.path.join(w, pair.replace('/', '_'))
        run(['/usr/bin/python3', MAKE_STREAMS, dense, s, '--format', 'csv',
             '--accel-rate', ar, '--gyro-rate', gr, '--seed', str(seed)], check=True)
        cals = {}
        for kind, args in (('two', [os.path.join(s, 'accel.csv'), '--gyro-log',
                                    os.path.join(s, 'gyro.csv')]),
                           ('single@a', [os.path.join(s, 'single_at_accel.csv')]),
                           ('single@g', [os.path.join(s, 'single_at_gyro.csv')])):
            out = os.path.join(s, kind + '.json')
            r = run([mpcal, 'calibrate'] + args + ['-o', out])
            if r.returncode == 0:
                with open(out) as f:
                    cals[kind] = params(json.load(f))
            else:
                cals[kind] = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else 'failed'
        shutil.rmtree(s)
        results[pair] = cals
    os.remove(dense)
    return seed, truth, results


def stats(zs):
    if not zs:
        return '-'
    n = len(zs)
    rms = math.sqrt(sum(z * z for z in zs) / n)
    mean = sum(zs) / n
    return '%.2f %+.2f' % (rms, mean)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mpcal')
    ap.add_argument('--seeds', default='1-40', help='first-last (default 1-40)')
    ap.add_argument('--rates', default='63/200,250/400',
                    help='accelerometer/gyroscope rates in Hz, comma-separated')
    ap.add_argument('--jobs', type=int, default=2)
    args = ap.parse_args()
    first, last = (int(x) for x in args.seeds.split('-'))
    rates = args.rates.split(',')
    mpcal = os.path.abspath(args.mpcal)
    workdir = tempfile.mkdtemp(prefix='streams_mc.')
    try:
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            done = list(pool.map(lambda s: one_seed(mpcal, s, rates, workdir),
                                 range(first, last + 1)))
    finally:
        shutil.rmtree(workdir, ignore_errors=True)

    print('seeds %d-%d; each cell: RMS z, mean z over the parameters of every calibrated seed'
          % (first, last))
    print('%-9s %-9s %-6s %-12s %-12s %-12s' % ('rates', 'file', 'seeds', 'accel', 'gyro m',
                                                'gyro bias'))
    for pair in rates:
        for kind in ('single@a', 'single@g', 'two'):
            z = {'accel': [], 'm': [], 'b': []}
            n = 0
            for _, truth, res in done:
                cal = res[pair][kind]
                if isinstance(cal, str):
                    continue
                n += 1
                for (g, _, t, _), (_, _, v, s) in zip(truth, cal):
                    z[g].append((v - t) / s)
            print('%-9s %-9s %-6d %-12s %-12s %-12s' % (pair, kind, n, stats(z['accel']),
                                                       stats(z['m']), stats(z['b'])))
    print()
    print('differences: RMS z, mean z, largest |z| over the parameters of every seed')
    print('%-9s %-36s %-20s %-20s %-20s' % ('rates', 'compared', 'accel', 'gyro m', 'gyro bias'))

    def diff_row(pair, a, b, how, label):
        z = {'accel': [], 'm': [], 'b': []}
        for _, _, res in done:
            ca, cb = res[pair][a], res[pair][b]
            if isinstance(ca, str) or isinstance(cb, str):
                continue
            for (g, _, va, sa), (_, _, vb, sb) in zip(ca, cb):
                z[g].append((va - vb) / how(sa, sb))
        cell = lambda zs: (stats(zs) + ' %.2f' % max(abs(x) for x in zs)) if zs else '-'
        print('%-9s %-36s %-20s %-20s %-20s' % (pair, label, cell(z['accel']), cell(z['m']),
                                               cell(z['b'])))

    for pair in rates:
        diff_row(pair, 'single@a', 'single@g', lambda sa, sb: sb, 'single@a - single@g, / σ(single@g)')
        diff_row(pair, 'single@a', 'single@g', lambda sa, sb: math.hypot(sa, sb),
                 'single@a - single@g, / √(σa²+σg²)')
        diff_row(pair, 'two', 'single@g', lambda sa, sb: sa, 'two - single@g, / σ(two)')
        diff_row(pair, 'two', 'single@a', lambda sa, sb: sa, 'two - single@a, / σ(two)')
    failed = [(s, p, k, c) for s, _, res in done for p in rates for k, c in res[p].items()
              if isinstance(c, str)]
    for s, p, k, c in failed:
        print('seed %d %s %s not calibrated: %s' % (s, p, k, c[:90]))


if __name__ == '__main__':
    main()
