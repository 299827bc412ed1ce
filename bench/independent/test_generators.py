#!/usr/bin/env python3
"""Tests of the independent generators themselves (plain asserts; python3 + numpy).

Each generator's self-check must pass on short sessions, through the command
line and in every unit option; and must FAIL when the truth it checks against
is wrong (a check that cannot fail tests nothing).  About 30 s.

  python3 bench/independent/test_generators.py [--keep DIR]

Exit status 0 when every test passes; the failing assert otherwise.
"""
import argparse
import contextlib
import copy
import csv
import io
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from _numpy import need_numpy  # noqa: E402

need_numpy()
import numpy as np  # noqa: E402
import gen_imu_session  # noqa: E402
import gen_still  # noqa: E402
import imu_check  # noqa: E402
import so3  # noqa: E402
import still_check  # noqa: E402


def run_cli(script, *args):
    r = subprocess.run([sys.executable, os.path.join(HERE, script), *args], capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def quiet(fn, *args):
    """fn(*args) with its printed lines captured; returns (result, text)."""
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        result = fn(*args)
    return result, buf.getvalue()


def test_so3_body_rate(_):
    """J_r(v) dv/dt is the body rate of Exp(v(t)) (against a finite difference)."""
    rng = np.random.default_rng(5)
    for _ in range(20):
        v0, vd = rng.normal(0, 1, 3), rng.normal(0, 1, 3)
        h = 1e-6
        qp, qm = so3.exp(v0 + h * vd), so3.exp(v0 - h * vd)
        w_num = 2 * so3.mul(so3.conj(so3.exp(v0)), (qp - qm) / (2 * h))[1:]
        assert np.allclose(so3.right_jacobian_apply(v0, vd), w_num, atol=1e-8), (v0, vd)
    q = so3.exp(np.array([0.3, -1.2, 0.5]))
    assert np.allclose(so3.log(q), [0.3, -1.2, 0.5])
    assert abs(so3.angle_between(q, so3.mul(q, so3.exp([1e-9, 0, 0]))) - 1e-9) < 1e-15


def test_imu_cli(tmp):
    """--check passes through the command line in each unit; files as documented."""
    for i, opts in enumerate([['--accel-units', 'g', '--gyro-units', 'dps'],
                              ['--accel-units', 'counts', '--gyro-units', 'counts', '--earth-rate', 'off'],
                              ['--rate', '50', '--lever-arm', '0', '--tremor', '0']]):
        out = os.path.join(tmp, 'imu%d' % i)
        code, stdout, stderr = run_cli('gen_imu_session.py', '--out', out, '--seed', str(10 + i),
                                       '--positions', '8', '--check', *opts)
        assert code == 0, stdout + stderr
        assert stdout.count(': ok') == 3, stdout
        with open(os.path.join(out, 'session.csv')) as f:
            rows = list(csv.reader(f))
        assert rows[0] == ['t', 'ax', 'ay', 'az', 'gx', 'gy', 'gz'], rows[0]
        with open(os.path.join(out, 'truth.json')) as f:
            truth = json.load(f)
        assert len(rows) - 1 == truth['samples']
        assert len(truth['static_intervals']) == 8 and len(truth['turns']) == 7
        rate = truth['rate_hz']
        assert abs(float(rows[-1][0]) - truth['duration_s']) < 1e-6
        for st in truth['static_intervals']:
            assert abs(st['start_s'] * rate - round(st['start_s'] * rate)) < 1e-6
            assert 5 <= st['end_s'] - st['start_s'] <= 40.01
        for t in truth['turns']:
            assert 1 <= t['end_s'] - t['start_s'] <= 4.01
            assert t['path_angle_rad'] >= t['angle_rad'] - 1e-9
        m = np.array(truth['gyroscope']['M']).reshape(3, 3)
        assert np.allclose(m @ np.array(truth['gyroscope']['M_inverse']).reshape(3, 3), np.eye(3))
        assert np.all(abs(np.diag(m) - 1) <= 0.06) and np.all(abs(m[~np.eye(3, dtype=bool)]) <= 0.03)
    # same seed, same files
    code, _, _ = run_cli('gen_imu_session.py', '--out', os.path.join(tmp, 'again'), '--seed', '10',
                         '--positions', '8', '--accel-units', 'g', '--gyro-units', 'dps')
    with open(os.path.join(tmp, 'imu0', 'session.csv')) as a, open(os.path.join(tmp, 'again', 'session.csv')) as b:
        assert code == 0 and a.read() == b.read()
    code, _, stderr = run_cli('gen_imu_session.py', '--out', os.path.join(tmp, 'bad'), '--seed', '1',
                              '--positions', '1')
    assert code != 0 and '--positions' in stderr


def test_imu_turn_axes_vary(tmp):
    """Turns are about varied axes, and not about one axis within a turn."""
    args = gen_imu_session.parse_args(['--out', os.path.join(tmp, 'axes'), '--seed', '3', '--positions', '26'])
    sim, truth = quiet(gen_imu_session.generate, args)[0]
    axes = np.array([t['axis_body'] for t in truth['turns']])
    assert np.linalg.svd(axes, compute_uv=False).min() > 0.3 * math.sqrt(len(axes) / 3)
    excess = [t['path_angle_rad'] / t['angle_rad'] for t in truth['turns'] if t['angle_rad'] > 0.3]
    assert np.median(excess) > 1.03, excess
    kinds = {st['target_kind'] for st in truth['static_intervals']}
    assert kinds == {'face', 'edge', 'corner'}


def test_imu_check_fails_on_wrong_truth(tmp):
    """(b) fails with M = I or a bias off by 3 sigma of the turn; (c) with a wrong accelerometer bias."""
    args = gen_imu_session.parse_args(['--out', os.path.join(tmp, 'wrong'), '--seed', '4', '--positions', '12'])
    sim, truth = quiet(gen_imu_session.generate, args)[0]
    ok, text = quiet(imu_check.run, sim, args.out, truth)
    assert ok, text
    bad = copy.deepcopy(truth)
    bad['gyroscope']['M'] = list(np.eye(3).ravel())
    ok, text = quiet(imu_check.run, sim, args.out, bad)
    assert not ok and '(b) gyro carries gravity k -> k+1: FAILED' in text, text
    shifted = dict(sim, bias=sim['bias'] + 5 * sim['gyro']['noise_density_radps_per_sqrt_hz'] / math.sqrt(2.0))
    ok, text = quiet(imu_check.run, shifted, args.out, truth)
    assert not ok and '(b) gyro carries gravity k -> k+1: FAILED' in text, text
    bad = copy.deepcopy(truth)
    bad['accelerometer']['bias_mps2'][1] += 5 * sim['acc']['sigma_per_sample_mps2'] / math.sqrt(5 * args.rate)
    ok, text = quiet(imu_check.run, sim, args.out, bad)
    assert not ok and '(c) static means: FAILED' in text, text


def test_still_cli(tmp):
    out = os.path.join(tmp, 'still')
    code, stdout, stderr = run_cli('gen_still.py', '--out', out, '--hours', '0.1', '--rate', '100', '--seed', '2',
                                   '--quantisation', '--accel-units', 'g', '--gyro-units', 'dps', '--check')
    assert code == 0, stdout + stderr
    assert stdout.count(': ok') == 6 and 'FAILED' not in stdout, stdout
    with open(os.path.join(out, 'truth.json')) as f:
        truth = json.load(f)
    assert truth['samples'] == 36000
    for sensor in ('accel', 'gyro'):
        assert all(0.95 < r < 1.06 for r in truth[sensor]['plateau_ripple'])
    code, _, stderr = run_cli('gen_still.py', '--out', out, '--hours', '0', '--rate', '100', '--seed', '2')
    assert code != 0 and '--hours' in stderr


def test_still_given_terms_and_failures(tmp):
    """Given N, K, B are used as given; the check fails when the truth is off."""
    args = gen_still.parse_args(['--out', os.path.join(tmp, 'still2'), '--hours', '0.1', '--rate', '100',
                                 '--seed', '6', '--quantisation', '--gyro-noise-density', '2e-4',
                                 '--gyro-bias-instability', '3e-5', '--gyro-random-walk', '1e-6'])
    truth, stats = quiet(gen_still.generate, args)[0]
    assert truth['gyro']['noise_density_radps_per_sqrt_hz'] == [2e-4] * 3
    assert truth['gyro']['bias_instability_radps'] == [3e-5] * 3
    ok, text = quiet(still_check.run, stats, truth, args.out)
    assert ok, text
    for key, i, factor, label in (('noise_density_mps2_per_sqrt_hz', 0, 1.05, 'white variance'),
                                  ('random_walk_radps2_per_sqrt_hz', 2, 1.05, 'random-walk increment'),
                                  ('bias_instability_mps2', 1, 1.3, 'bias-instability part'),
                                  ('quantisation_rad', 0, 0.0, 'sample intervals')):
        bad = copy.deepcopy(truth)
        sensor = 'accel' if 'mps' in key else 'gyro'
        bad[sensor][key][i] *= factor
        ok, text = quiet(still_check.run, stats, bad, args.out)
        failed = [line for line in text.splitlines() if 'FAILED' in line]
        assert not ok and any(label in line for line in failed), (key, text)


def test_still_real_effects(tmp):
    """The low-pass, the Gauss-Markov bump and the sinusoid follow their exact
    Allan curves; the check fails when any of them is left out of the truth."""
    args = gen_still.parse_args(['--out', os.path.join(tmp, 'still3'), '--hours', '0.1', '--rate', '100',
                                 '--seed', '7', '--gyro-noise-density', '2e-4', '--lowpass-hz', '12.5',
                                 '--gm-tau-c', '0.5', '--gyro-gm-sigma', '1e-3', '--sine-period', '0.2',
                                 '--gyro-sine-amplitude', '2e-3'])
    truth, stats = quiet(gen_still.generate, args)[0]
    assert truth['lowpass_hz'] == 12.5 and truth['gyro']['gauss_markov_bump']['tau_c_s'] == 0.5
    ok, text = quiet(still_check.run, stats, truth, args.out)
    assert ok, text
    for label, spoil in (('low-pass', lambda t: t.update(lowpass_hz=0.0)),
                         ('bump', lambda t: t['gyro']['gauss_markov_bump']['sigma_radps'].__setitem__(0, 0.0)),
                         ('sine', lambda t: t['gyro']['sine']['amplitude_radps'].__setitem__(1, 0.0))):
        bad = copy.deepcopy(truth)
        spoil(bad)
        ok, text = quiet(still_check.run, stats, bad, args.out)
        failed = [line for line in text.splitlines() if 'FAILED' in line]
        assert not ok and any('Allan deviation of the total' in line for line in failed), (label, text)
    code, _, stderr = run_cli('gen_still.py', '--out', args.out, '--hours', '0.1', '--rate', '100',
                              '--seed', '7', '--lowpass-hz', '60')
    assert code != 0 and '--lowpass-hz' in stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--keep', help='write the generated files here and keep them')
    a = ap.parse_args()
    tests = [v for k, v in globals().items() if k.startswith('test_')]
    with (contextlib.nullcontext(a.keep) if a.keep else tempfile.TemporaryDirectory(prefix='mpcal_gen.')) as tmp:
        os.makedirs(tmp, exist_ok=True)
        for test in tests:
            test(tmp)
            print('ok  %s' % test.__name__)
    print('%d tests passed' % len(tests))
    return 0


if __name__ == '__main__':
    sys.exit(main())
