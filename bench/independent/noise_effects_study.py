#!/usr/bin/env python3
"""mpcal noise on gen_still.py records with one effect of real sensors.

  noise_effects_study.py MPCAL --effect plain|lowpass|bump|sine
                         [--hours H] [--rate R] [--seeds FIRST LAST] [--work DIR]

Per seed a record of H hours at R Hz (the terms drawn from the seed as
gen_still.py draws them) with the effect:
  plain    only the IEEE terms (N, B, K)
  lowpass  white noise through a first-order low-pass at R/8 Hz
  bump     a Gauss-Markov bump, tau_c 0.3 s, sigma 0.002 m/s^2 / 2e-4 rad/s
  sine     a sinusoid of period 2 s, 0.003 m/s^2 / 3e-4 rad/s
then `mpcal noise --whole --json` on it.  Prints per axis the model check
(fits or MISSES, cluster times outside, where the fit begins), the white
noise's status and N / true N - 1, and a summary: axes where the model fits,
and the largest |N / true N - 1| of the axes where N is measured.  The
records are kept in --work (default a temporary directory removed after).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EFFECTS = {
    'plain': lambda rate: [],
    'lowpass': lambda rate: ['--lowpass-hz', str(rate / 8)],
    'bump': lambda rate: ['--gm-tau-c', '0.3', '--accel-gm-sigma', '0.002', '--gyro-gm-sigma', '2e-4'],
    'sine': lambda rate: ['--sine-period', '2', '--accel-sine-amplitude', '0.003',
                          '--gyro-sine-amplitude', '3e-4'],
}
SENSORS = (('accelerometer', 'accel', 'mps2'), ('gyroscope', 'gyro', 'radps'))


def one(mpcal, work, effect, seed, hours, rate):
    out = os.path.join(work, '%s_%d' % (effect, seed))
    subprocess.run([sys.executable, os.path.join(HERE, 'gen_still.py'), '--out', out, '--hours', str(hours),
                    '--rate', str(rate), '--seed', str(seed)] + EFFECTS[effect](rate),
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run([mpcal, 'noise', os.path.join(out, 'still.csv'), '--whole', '--json',
                    os.path.join(out, 'noise.json')], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, 'noise.json')) as f:
        result = json.load(f)
    with open(os.path.join(out, 'truth.json')) as f:
        truth = json.load(f)
    rows = []
    for sensor, key, u in SENSORS:
        for i, ax in enumerate('xyz'):
            a = result[sensor]['axes'][ax]
            c, n = a['model_check'], a['white_noise_%s_per_rthz' % u]
            err = n['value'] / truth[key]['noise_density_%s_per_sqrt_hz' % u][i] - 1 if 'value' in n else None
            rows.append((key + ax, c, n['status'], err))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mpcal')
    ap.add_argument('--effect', choices=sorted(EFFECTS), required=True)
    ap.add_argument('--hours', type=float, default=1.0)
    ap.add_argument('--rate', type=float, default=100.0)
    ap.add_argument('--seeds', type=int, nargs=2, default=(1, 6), metavar=('FIRST', 'LAST'))
    ap.add_argument('--work', help='keep the records here')
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix='mpcal_effects.') as tmp:
        work = a.work or tmp
        os.makedirs(work, exist_ok=True)
        fits = total = 0
        errs = []
        for seed in range(a.seeds[0], a.seeds[1] + 1):
            for name, c, status, err in one(a.mpcal, work, a.effect, seed, a.hours, a.rate):
                total += 1
                fits += c['fits']
                if err is not None:
                    errs.append(abs(err))
                print('seed %d %s %s %d/%d from %.3g s  N %s %s' % (
                    seed, name, 'fits' if c['fits'] else 'MISSES', c['outside'], c['points'], c['from_tau_s'],
                    status, '%+.4f' % err if err is not None else '-'))
        print('%s, %g h at %g Hz: the model fits %d of %d axes; N measured on %d, largest |N/true - 1| %s'
              % (a.effect, a.hours, a.rate, fits, total, len(errs), '%.4f' % max(errs) if errs else '-'))
    return 0


if __name__ == '__main__':
    sys.exit(main())
