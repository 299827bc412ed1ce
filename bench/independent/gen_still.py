#!/usr/bin/env python3
"""Independent still recording with known noise terms (accelerometer + gyroscope).

Written from docs/method.md §8 and IEEE Std 952/1293, without reading
mpcal's simulator or noise estimators, so that studies can test an Allan
analysis on data its authors did not make.

  gen_still.py --out DIR --hours H --rate R --seed S
               [--gravity-axis z|-z|x|-x|y|-y] [--quantisation]
               [--accel-units mps2|g] [--gyro-units rads|dps]
               [--accel-noise-density N] [--accel-bias-instability B]
               [--accel-random-walk K] [--gyro-noise-density N]
               [--gyro-bias-instability B] [--gyro-random-walk K] [--check]

writes DIR/still.csv (header t,ax,ay,az,gx,gy,gz; t in s) and
DIR/truth.json; the same arguments always give the same files.  The rows are
written as they are made (numpy chunks of about 2^18 samples), so memory does
not grow with H: 8 h at 400 Hz is 11.5 M rows, about 0.94 GB.  Example:

  gen_still.py --out /tmp/still --hours 2 --rate 200 --seed 3 --check

The sensor never moves: each axis reads a constant (turn-on bias; plus the
gravity magnitude 9.80665 m/s^2 on the accelerometer axis --gravity-axis,
default z; the gyroscope constant includes whatever the Earth rate adds)
plus independent noise terms, per axis, in continuous-time coefficients (SI):

  N  white noise density     accel m/s^2/sqrt(Hz)   gyro rad/s/sqrt(Hz)
     per-sample sigma N sqrt(R); Allan deviation N / sqrt(tau)
  K  rate random walk        accel m/s^3/sqrt(Hz)   gyro rad/s^2/sqrt(Hz)
     increments K sqrt(1/R) per sample; Allan deviation K sqrt(tau / 3)
  B  bias instability        accel m/s^2            gyro rad/s
     a sum of fifteen first-order Gauss-Markov processes, correlation times
     0.01-100000 s two per decade, equal variance, scaled so that the median
     of their exact Allan deviation over 0.1-10000 s is 0.664 B (flat there
     within the "plateau_ripple" of the truth, about +-1.3 %: over every
     cluster time an analysis of a record up to 11 h fits; see noise_terms).  Reading B as
     min(Allan deviation) / 0.664 gives B where N and K are small at the
     minimum; the truth also gives that textbook reading of the total curve.
  Q  quantisation (--quantisation): the integrated signal rounded to steps
     of sqrt(12) Q; Allan deviation sqrt(3) Q / tau.

Without the coefficient options the values are drawn per axis from the seed:
accelerometer N 60-250 ug/sqrt(Hz), B 5-50 ug; gyroscope N 0.003-0.012
deg/s/sqrt(Hz), B 1-15 deg/h; K so that the random-walk line crosses 0.664 B
at tau 1000-5000 s; Q (with --quantisation) so that the quantisation line
crosses the white line at 0.1-0.25 sample intervals: it adds 10-25 % to
the Allan variance at one sample interval and its step stays below the
per-sample noise of the integrated signal, so the rounding errors are
independent and uniform and 3 Q^2 / tau^2 is exact (with coarser steps
they are not, and the Allan variance at one sample departs from it by ~1 %).  A coefficient option sets that
term on all three axes.

truth.json: per sensor and axis N, K, B, Q (SI and datasheet units), the
Gauss-Markov set, the per-sample sigmas, and the exact expected Allan
deviation of each term and of the sum at log-spaced tau ("allan").

--check: the Allan deviation of the total at 1, 2 and 4 sample intervals
(where quantisation shows) against the exact curve; the sample variance of the generated white part and of the
random-walk increments against N^2 R and K^2 / R (within 4 standard errors);
the Allan deviation of the bias-instability part alone and of the written
total, from 0.1 s block sums, against the exact curves at 1, 10, 100, 1000 s
(where the record holds 20 such clusters; within 4 times the rough relative
error 1/sqrt(2 (L/m - 1))); the first rows of still.csv read back.  Exit 1 on
failure.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _numpy import need_numpy  # noqa: E402

need_numpy()
import numpy as np  # noqa: E402
import noise_terms  # noqa: E402
import still_check  # noqa: E402

G_STD = 9.80665
DEG = math.pi / 180
UG = 1e-6 * G_STD
CHUNK = 1 << 18
BLOCK_S = 0.1
FORMAT = 'mpcal.independent.still/1'
AXES = ('x', 'y', 'z')


def draw_terms(rng, args, rate_hz):
    """Per sensor and axis: constant, N, K, B, Q (SI)."""
    out = {}
    specs = {'accel': (60 * UG, 250 * UG, 5 * UG, 50 * UG, 0.05 * G_STD),
             'gyro': (0.003 * DEG, 0.012 * DEG, 1 * DEG / 3600, 15 * DEG / 3600, 1 * DEG)}
    for sensor, (nlo, nhi, blo, bhi, const) in specs.items():
        axes = []
        for a in AXES:
            n = getattr(args, sensor + '_noise_density') or rng.uniform(nlo, nhi)
            b = getattr(args, sensor + '_bias_instability')
            b = rng.uniform(blo, bhi) if b is None else b
            k = getattr(args, sensor + '_random_walk')
            k = noise_terms.FLICKER_FACTOR * b * math.sqrt(3 / rng.uniform(1000, 5000)) if k is None else k
            q = 0.0
            if args.quantisation:  # the Q line sqrt(3) Q / tau meets N / sqrt(tau) at 0.1-0.25 samples
                q = n * math.sqrt(rng.uniform(0.1, 0.25) / rate_hz / 3)
            c = rng.uniform(-const, const)
            if sensor == 'accel' and args.gravity_axis[-1] == a:
                c += G_STD * (-1 if args.gravity_axis.startswith('-') else 1)
            axes.append({'constant': c, 'N': n, 'K': k, 'B': b, 'Q': q, 'lowpass_hz': args.lowpass_hz,
                         'bump': (getattr(args, sensor + '_gm_sigma'), args.gm_tau_c),
                         'sine': (getattr(args, sensor + '_sine_amplitude'), args.sine_period)})
        out[sensor] = axes
    return out


def allan_table(terms, rate_hz, duration_s):
    tau0 = 1.0 / rate_hz
    tau = np.unique(np.round(np.logspace(0, math.log10(max(2.0, duration_s / 2 * rate_hz)), 61)) * tau0)
    out = {'tau_s': tau.tolist()}
    for sensor, axes in terms.items():
        per = {}
        for ax in axes:
            q2 = noise_terms.gm_variance_for(ax['B'], tau0)[0] if ax['B'] > 0 else 0.0
            parts = noise_terms.allan_var_terms(tau, tau0, ax['N'], ax['K'], q2, ax['Q'],
                                                ax['lowpass_hz'], ax['bump'], ax['sine'])
            total = sum(parts.values())
            for name, v in list(parts.items()) + [('total', total)]:
                per.setdefault(name, []).append(np.sqrt(v).tolist())
            i = int(np.argmin(total))
            ax['textbook_B_from_total_min'] = float(math.sqrt(total[i]) / noise_terms.FLICKER_FACTOR)
            ax['tau_at_total_min_s'] = float(tau[i])
        out[sensor] = per
    return out


def datasheet(sensor, ax):
    if sensor == 'accel':
        return {'N_ug_per_sqrt_hz': ax['N'] / UG, 'N_mps_per_sqrt_h': ax['N'] * 60,
                'B_ug': ax['B'] / UG, 'K_ug_per_sqrt_s': ax['K'] / UG}
    return {'N_deg_per_sqrt_h': ax['N'] / DEG * 60, 'N_dps_per_sqrt_hz': ax['N'] / DEG,
            'B_deg_per_h': ax['B'] / DEG * 3600, 'K_deg_per_h_per_sqrt_h': ax['K'] / DEG * 3600 * 60}


def write_still(args, terms, rng):
    """Streams still.csv; returns the statistics the check needs."""
    rate = args.rate
    n_total = int(round(args.hours * 3600 * rate))
    nb = max(1, int(round(BLOCK_S * rate)))
    chunk = nb * max(1, CHUNK // nb)
    axes = [noise_terms.Axis(rng, rate, a['constant'], a['N'], a['K'], a['B'], a['Q'],
                             a['lowpass_hz'], a['bump'], a['sine'])
            for sensor in ('accel', 'gyro') for a in terms[sensor]]
    for ax, a in zip(axes, terms['accel'] + terms['gyro']):
        a['gauss_markov_sigma'] = math.sqrt(ax.q2)
        a['plateau_ripple'] = ax.ripple
        a['sine_phase'] = ax.sine_phase
    afac = G_STD if args.accel_units == 'g' else 1.0
    gfac = DEG if args.gyro_units == 'dps' else 1.0
    fmt = ','.join(['%.6f'] + ['%.9f' if afac != 1 else '%.7f'] * 3 + ['%.7f' if gfac != 1 else '%.9f'] * 3)
    stats = still_check.Stats(6, nb / rate)
    path = os.path.join(args.out, 'still.csv')
    tmp = path + '.part'
    with open(tmp, 'w') as f:
        f.write('t,ax,ay,az,gx,gy,gz\n')
        for start in range(0, n_total, chunk):
            n = min(chunk, n_total - start)
            cols, parts = zip(*(ax.next(n) for ax in axes))
            data = np.column_stack([np.arange(start, start + n) / rate] +
                                   [c / afac for c in cols[:3]] + [c / gfac for c in cols[3:]])
            stats.add(np.array(cols), parts, nb, first_rows=data[:still_check.READBACK_ROWS])
            f.write('\n'.join(map(fmt.__mod__, map(tuple, data.tolist()))) + '\n')
    os.replace(tmp, path)
    return stats, n_total, afac, gfac


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--out', required=True, help='output directory (created)')
    ap.add_argument('--hours', type=float, required=True, help='length of the recording in hours')
    ap.add_argument('--rate', type=float, required=True, help='sample rate in Hz')
    ap.add_argument('--seed', type=int, required=True, help='random seed; same seed, same files')
    ap.add_argument('--gravity-axis', choices=['x', '-x', 'y', '-y', 'z', '-z'], default='z',
                    help='accelerometer axis that points up (reads +g; -z: upside down); default z')
    ap.add_argument('--quantisation', action='store_true', help='add the quantisation term Q')
    ap.add_argument('--accel-units', choices=['mps2', 'g'], default='mps2')
    ap.add_argument('--gyro-units', choices=['rads', 'dps'], default='rads')
    for sensor, unit_n, unit_b, unit_k in (('accel', 'm/s^2/sqrt(Hz)', 'm/s^2', 'm/s^3/sqrt(Hz)'),
                                           ('gyro', 'rad/s/sqrt(Hz)', 'rad/s', 'rad/s^2/sqrt(Hz)')):
        ap.add_argument('--%s-noise-density' % sensor, type=float, metavar='N', help='N in ' + unit_n)
        ap.add_argument('--%s-bias-instability' % sensor, type=float, metavar='B',
                        help='B in %s (0: none)' % unit_b)
        ap.add_argument('--%s-random-walk' % sensor, type=float, metavar='K', help='K in %s (0: none)' % unit_k)
    ap.add_argument('--lowpass-hz', type=float, default=0.0, metavar='F',
                    help='white noise through a first-order IIR low-pass of bandwidth F Hz (0: none)')
    ap.add_argument('--gm-tau-c', type=float, default=1.0, metavar='S',
                    help='correlation time of the Gauss-Markov bump, s (default 1)')
    ap.add_argument('--accel-gm-sigma', type=float, default=0.0, metavar='S',
                    help='standard deviation of the accelerometer Gauss-Markov bump, m/s^2 (0: none)')
    ap.add_argument('--gyro-gm-sigma', type=float, default=0.0, metavar='S',
                    help='standard deviation of the gyroscope Gauss-Markov bump, rad/s (0: none)')
    ap.add_argument('--sine-period', type=float, default=1.0, metavar='P', help='period of the sinusoid, s')
    ap.add_argument('--accel-sine-amplitude', type=float, default=0.0, metavar='A',
                    help='amplitude of the accelerometer sinusoid, m/s^2 (0: none)')
    ap.add_argument('--gyro-sine-amplitude', type=float, default=0.0, metavar='A',
                    help='amplitude of the gyroscope sinusoid, rad/s (0: none)')
    ap.add_argument('--check', action='store_true', help='verify the noise terms after writing')
    a = ap.parse_args(argv)
    if not 0 < a.hours <= 48:
        ap.error('--hours must be in (0, 48]')
    if not 1 <= a.rate <= 10000:
        ap.error('--rate must be 1-10000 Hz')
    if a.hours * 3600 * a.rate < 100:
        ap.error('the recording must hold at least 100 samples (--hours x 3600 x --rate)')
    if not 0 <= a.lowpass_hz < a.rate / 2:
        ap.error('--lowpass-hz must be in [0, rate/2)')
    for name in ('gm_tau_c', 'sine_period'):
        if not getattr(a, name) > 0:
            ap.error('--%s must be positive' % name.replace('_', '-'))
    if a.sine_period < 2 / a.rate:
        ap.error('--sine-period must be at least two sample intervals (2 / --rate)')
    for name in ('accel_gm_sigma', 'gyro_gm_sigma', 'accel_sine_amplitude', 'gyro_sine_amplitude'):
        if getattr(a, name) < 0:
            ap.error('--%s must not be negative' % name.replace('_', '-'))
    for name in ('accel_noise_density', 'gyro_noise_density'):
        if getattr(a, name) is not None and getattr(a, name) <= 0:
            ap.error('--%s must be positive' % name.replace('_', '-'))
    for name in ('accel_bias_instability', 'accel_random_walk', 'gyro_bias_instability', 'gyro_random_walk'):
        if getattr(a, name) is not None and getattr(a, name) < 0:
            ap.error('--%s must not be negative' % name.replace('_', '-'))
    return a


def generate(args):
    """Writes still.csv and truth.json; returns (truth, the statistics for the check)."""
    os.makedirs(args.out, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    terms = draw_terms(rng, args, args.rate)
    stats, n_total, afac, gfac = write_still(args, terms, rng)
    duration = n_total / args.rate
    allan = allan_table(terms, args.rate, duration)
    truth = {'format': FORMAT, 'generator': 'bench/independent/gen_still.py', 'seed': args.seed,
             'rate_hz': args.rate, 'hours': args.hours, 'samples': n_total, 'duration_s': duration,
             'gravity_mps2': G_STD, 'gravity_axis': args.gravity_axis,
             'log': {'file': 'still.csv', 'columns': 't,ax,ay,az,gx,gy,gz',
                     'accel_units': args.accel_units, 'gyro_units': args.gyro_units,
                     'accel_si_per_unit': afac, 'gyro_si_per_unit': gfac},
             'lowpass_hz': args.lowpass_hz,
             'conventions': {'N': 'white noise density; per-sample sigma N sqrt(rate_hz)',
                             'lowpass_hz': 'white noise through y_n = a y_(n-1) + (1 - a) x_n, '
                                           'a = exp(-2 pi lowpass_hz / rate_hz); 0: none',
                             'gauss_markov_bump': 'x_n = phi x_(n-1) + w_n, phi = exp(-1 / (rate_hz tau_c_s)), '
                                                  'stationary standard deviation sigma',
                             'sine': 'amplitude sin(2 pi t / period_s + phase)',
                             'K': 'rate random walk; increments K sqrt(1/rate_hz) per sample',
                             'B': 'bias instability; flat Allan deviation 0.664 B over plateau_s',
                             'Q': 'quantisation; Allan deviation sqrt(3) Q / tau'},
             'bias_instability_model': {'gauss_markov_tau_c_s': list(noise_terms.TAU_C_S),
                                        'plateau_s': list(noise_terms.PLATEAU_S),
                                        'flicker_factor': noise_terms.FLICKER_FACTOR}}
    units = {'accel': ('mps2', 'mps2_per_sqrt_hz', 'mps3_per_sqrt_hz', 'mps'),
             'gyro': ('radps', 'radps_per_sqrt_hz', 'radps2_per_sqrt_hz', 'rad')}
    for sensor, (u, un, uk, uq) in units.items():
        axes = terms[sensor]
        truth[sensor] = {
            'constant_' + u: [a['constant'] for a in axes],
            'noise_density_' + un: [a['N'] for a in axes],
            'random_walk_' + uk: [a['K'] for a in axes],
            'bias_instability_' + u: [a['B'] for a in axes],
            'quantisation_' + uq: [a['Q'] for a in axes],
            'sigma_white_per_sample_' + u: [a['N'] * math.sqrt(args.rate) for a in axes],
            'random_walk_step_per_sample_' + u: [a['K'] * math.sqrt(1 / args.rate) for a in axes],
            'gauss_markov_sigma_' + u: [a['gauss_markov_sigma'] for a in axes],
            'plateau_ripple': [a['plateau_ripple'] for a in axes],
            'textbook_B_from_total_min_' + u: [a['textbook_B_from_total_min'] for a in axes],
            'tau_at_total_min_s': [a['tau_at_total_min_s'] for a in axes],
            'gauss_markov_bump': {'sigma_' + u: [a['bump'][0] for a in axes], 'tau_c_s': args.gm_tau_c},
            'sine': {'amplitude_' + u: [a['sine'][0] for a in axes], 'period_s': args.sine_period,
                     'phase_rad': [a['sine_phase'] for a in axes]},
            'datasheet': dict(zip(AXES, (datasheet(sensor, a) for a in axes)))}
    truth['allan'] = allan
    with open(os.path.join(args.out, 'truth.json'), 'w') as f:
        json.dump(truth, f, indent=1)
    return truth, stats


def main(argv=None):
    args = parse_args(argv)
    try:
        truth, stats = generate(args)
    except OSError as e:
        sys.exit('%s: error: cannot write %s: %s; give a writable --out directory'
                 % (os.path.basename(sys.argv[0]), args.out, e.strerror or e))
    n_total, duration = truth['samples'], truth['duration_s']
    print(json.dumps({'file': os.path.join(args.out, 'still.csv'), 'rows': n_total, 'duration_s': duration}))
    if args.check and not still_check.run(stats, truth, args.out):
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
