#!/usr/bin/env python3
"""mpcal's estimates and their 1σ on sessions that its own simulator did not make.

Generates sessions with gen_session.py (seeds S+1 .. S+N), runs `mpcal detect`
and `mpcal calibrate` on each with the options the generator names for its log
(units, gravity, columns, rate), and scores z = (estimate - truth) / reported σ
for the 9 parameters in the calibration file's frame. Unbiased estimates with a
right σ make z standard normal: RMS 1, |z| > 3 in 0.27 % of the values and
|z| > 4 in 0.0063 %.

PASS when every session ran (both commands exit 0 and find every generated
position, the initial rest included) and the RMS of z over all parameters is
within 0.8 - 1.25.

  study.py MPCAL_BINARY [--sessions N] [--seed-base S] [--workdir DIR]

Exit status 0 on PASS, 1 on FAIL. --workdir keeps each session's log, truth
(meta.json) and mpcal's output for a look afterwards.
"""
import argparse
import concurrent.futures
import contextlib
import json
import math
import os
import subprocess
import sys
import tempfile

GENERATOR = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'gen_session.py')
G_STD = 9.80665
PARAMETER_NAMES = ['bias_x_mps2', 'bias_y_mps2', 'bias_z_mps2',
                   'scale_factor_error_x', 'scale_factor_error_y', 'scale_factor_error_z',
                   'theta_yz_rad', 'theta_zx_rad', 'theta_zy_rad']
RMS_Z_BAR = (0.8, 1.25)


def truth_in_file_frame(config, mps2_per_unit):
    """The generator's true parameters as the calibration file states them.

    For counts the file's model acts on m * counts (m = its nominal m/s² per
    count, found from the data): with counts = zero + k * Y, its bias is
    m (zero + k b) and its scale factor m k (1 + s). In g and m/s² the file's
    frame is the generator's.
    """
    bias = config['bias_mps2']
    scale_error = config['sfe']
    theta = config['theta']
    if config['units'] == 'counts':
        counts_per_mps2 = config['counts']['cpg'] / G_STD
        zero = config['counts']['zero']
        bias = [mps2_per_unit * (zero + counts_per_mps2 * b) for b in bias]
        scale_error = [mps2_per_unit * counts_per_mps2 * (1 + s) - 1 for s in scale_error]
    return bias + scale_error + [theta['yz'], theta['zx'], theta['zy']]


def estimate_and_sigma(calibration):
    angles = calibration['non_orthogonality_rad']
    angles_std = calibration['std']['non_orthogonality_rad']
    estimate = (calibration['bias_mps2'] + calibration['scale_factor_error'] +
                [angles['yz'], angles['zx'], angles['zy']])
    sigma = (calibration['std']['bias_mps2'] + calibration['std']['scale_factor_error'] +
             [angles_std['yz'], angles_std['zx'], angles_std['zy']])
    return estimate, sigma


def run_mpcal(mpcal, command, meta, output_options, directory):
    """Runs one mpcal command on the session; returns None or why it failed."""
    with open(os.path.join(directory, command + '.out'), 'w') as stdout:
        result = subprocess.run([mpcal, command, meta['file'], *meta['opts'], *output_options],
                                stdout=stdout, stderr=subprocess.PIPE, text=True)
    with open(os.path.join(directory, command + '.err'), 'w') as stderr:
        stderr.write(result.stderr)
    if result.returncode == 0:
        return None
    errors = [line for line in result.stderr.splitlines() if 'error' in line]
    return f'{command} exited {result.returncode}' + (f': {errors[0]}' if errors else '')


def score_session(mpcal, seed, directory):
    """Generates and calibrates one session; returns (z of the 9 parameters, None)
    or (None, why the session failed)."""
    subprocess.run([sys.executable, GENERATOR, '--seed', str(seed), '--out', directory],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(directory, 'meta.json')) as f:
        meta = json.load(f)
    detection_path = os.path.join(directory, 'detection.json')
    calibration_path = os.path.join(directory, 'calibration.json')
    for command, output_options in (('detect', ['--json', detection_path]),
                                    ('calibrate', ['-o', calibration_path])):
        failure = run_mpcal(mpcal, command, meta, output_options, directory)
        if failure:
            return None, failure
    with open(detection_path) as f:
        found_by_detect = len(json.load(f)['intervals'])
    with open(calibration_path) as f:
        calibration = json.load(f)
    found_by_calibrate = len(calibration['positions'])
    generated = meta['positions_generated']  # the held positions and the initial rest
    if found_by_detect != generated or found_by_calibrate != generated:
        return None, (f'{generated} positions generated (rest included), detect found '
                      f'{found_by_detect}, calibrate {found_by_calibrate}')
    truth = truth_in_file_frame(meta['config'], calibration['input']['mps2_per_unit'])
    estimate, sigma = estimate_and_sigma(calibration)
    return [(e - t) / s if s > 0 else math.inf for e, t, s in zip(estimate, truth, sigma)], None


def run_sessions(mpcal, seeds, workdir):
    """Scores every seed, the sessions in parallel (each is a few subprocesses);
    returns {seed: (z, failure)}."""
    show_progress = sys.stderr.isatty()
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        futures = {pool.submit(score_session, mpcal, seed, os.path.join(workdir, f'seed_{seed}')): seed
                   for seed in seeds}
        for future in concurrent.futures.as_completed(futures):
            results[futures[future]] = future.result()
            if show_progress:
                print(f'\r{len(results)}/{len(seeds)} sessions', end='', file=sys.stderr, flush=True)
    if show_progress:
        print(file=sys.stderr)
    return results


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else math.nan


def report(seeds, results):
    """Prints the table; returns whether the study passes."""
    scored = [results[seed][0] for seed in seeds if results[seed][0] is not None]
    failures = [(seed, results[seed][1]) for seed in seeds if results[seed][1] is not None]
    print(f'independent: {len(seeds)} sessions (seeds {seeds[0]}-{seeds[-1]}) from '
          f'bench/independent/gen_session.py')
    for seed, failure in failures:
        print(f'  seed {seed} failed: {failure}')
    print(f'{"parameter":<22} {"RMS z":>8}')
    for p, name in enumerate(PARAMETER_NAMES):
        print(f'{name:<22} {rms([z[p] for z in scored]):>8.3f}')
    all_z = [v for z in scored for v in z]
    overall = rms(all_z)
    beyond = {k: sum(abs(v) > k for v in all_z) for k in (3, 4)}
    # Two-sided tail of the standard normal: 0.0027 beyond 3, 6.3e-5 beyond 4.
    expected = {k: len(all_z) * math.erfc(k / math.sqrt(2)) for k in (3, 4)}
    print(f'sessions run: {len(seeds)}, failed: {len(failures)}')
    print(f'all parameters: RMS z {overall:.3f} (bar: {RMS_Z_BAR[0]} - {RMS_Z_BAR[1]}); '
          f'|z| > 3: {beyond[3]} (normal: {expected[3]:.1f}); '
          f'|z| > 4: {beyond[4]} (normal: {expected[4]:.2f})')
    passed = not failures and RMS_Z_BAR[0] <= overall <= RMS_Z_BAR[1]
    print('PASS' if passed else 'FAIL')
    return passed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('mpcal', metavar='MPCAL_BINARY')
    parser.add_argument('--sessions', type=int, default=60)
    parser.add_argument('--seed-base', type=int, default=0,
                        help='the sessions are seeds SEED_BASE+1 .. SEED_BASE+SESSIONS')
    parser.add_argument('--workdir', help='keep the sessions here (default: a temporary '
                        'directory, removed at the end)')
    args = parser.parse_args()
    if args.sessions < 1:
        parser.error('--sessions must be at least 1')
    seeds = list(range(args.seed_base + 1, args.seed_base + args.sessions + 1))
    if args.workdir:
        os.makedirs(args.workdir, exist_ok=True)
        workdir = contextlib.nullcontext(args.workdir)
    else:
        workdir = tempfile.TemporaryDirectory(prefix='mpcal_independent.')
    with workdir as directory:
        passed = report(seeds, run_sessions(args.mpcal, seeds, directory))
    return 0 if passed else 1


if __name__ == '__main__':
    sys.exit(main())
