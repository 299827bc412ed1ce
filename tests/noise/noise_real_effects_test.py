#!/usr/bin/env python3
"""mpcal noise on still records with the effects of real sensors, written by
bench/independent/gen_still.py (not by mpcal's simulator): the fitted model is
held against the curve, the short-τ roll-off of a low-pass filter is cut off
and N read where the −½ slope begins, and an effect the model lacks is
flagged and its terms not presented as measured.

Each record is 30 min at 100 Hz (180,000 rows, about 2 s to write and 1 s to
analyse). The figures asserted follow from bench runs of 1 h at 100 Hz, 12
seeds: with the filter N came out within 1.7 % on every axis; without any
effect the model fit on 72 of 72 axes.

usage: noise_real_effects_test.py MPCAL_BINARY PROJECT_ROOT WORK_DIR
"""
import json
import math
import pathlib
import subprocess
import sys
from statistics import NormalDist

RATE_HZ = 100
HOURS = 0.5
AXES = ('x', 'y', 'z')
SENSORS = (('accelerometer', 'accel', 'mps2'), ('gyroscope', 'gyro', 'radps'))


def record(gen, work, name, seed, *extra):
    out = work / name
    # gen_still.py finds Debian's numpy itself (bench/independent/_numpy.py).
    subprocess.run([sys.executable, str(gen), '--out', str(out), '--hours', str(HOURS),
                    '--rate', str(RATE_HZ), '--seed', str(seed), *extra],
                   check=True, stdout=subprocess.DEVNULL)
    with open(out / 'truth.json') as f:
        return out, json.load(f)


def analyse(mpcal, out, *extra):
    run = subprocess.run([mpcal, 'noise', str(out / 'still.csv'), '--whole',
                          '--json', str(out / 'noise.json'), '--kalibr', str(out / 'imu.yaml'),
                          *extra],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(out / 'noise.json') as f:
        result = json.load(f)
    return result, run.stdout, (out / 'imu.yaml').read_text()


def axes(result, truth):
    """(name, axis JSON, white-noise key, true N) for the six axes."""
    for sensor, key, u in SENSORS:
        for i, a in enumerate(AXES):
            yield (key + a, result[sensor]['axes'][a], 'white_noise_%s_per_rthz' % u,
                   truth[key]['noise_density_%s_per_sqrt_hz' % u][i])


def test_plain(mpcal, gen, work):
    """Only the IEEE terms: the model fits every axis, nothing is cut, no
    bump or sinusoid is admitted."""
    out, truth = record(gen, work, 'plain', 21)
    result, text, _ = analyse(mpcal, out)
    for name, ax, wkey, n_true in axes(result, truth):
        c = ax['model_check']
        assert c['fits'] and c['excluded_points'] == 0, (name, c)
        assert c['share_outside'] <= 0.25, (name, c)
        n = ax[wkey]
        assert n['status'] == 'measured' and abs(n['value'] / n_true - 1) < 0.03, (name, n, n_true)
        assert ax['gauss_markov']['status'] == 'not_seen', (name, ax['gauss_markov'])
        assert ax['sinusoid']['status'] == 'not_seen', (name, ax['sinusoid'])
    assert 'model vs curve' in text and 'MISSES' not in text, text


def test_lowpass(mpcal, gen, work):
    """White noise through a first-order low-pass at an eighth of the rate:
    the short-τ end is cut where the −½ slope begins, N within 3 %."""
    out, truth = record(gen, work, 'lowpass', 22, '--lowpass-hz', str(RATE_HZ / 8))
    result, text, yaml = analyse(mpcal, out)
    tau0 = 1.0 / RATE_HZ
    for name, ax, wkey, n_true in axes(result, truth):
        c = ax['model_check']
        assert c['fits'] and c['excluded_points'] > 0, (name, c)
        # The filter's correlation time is 1/(2π F) = 1.3 τ0: its roll-off
        # is gone within a few tenths of a second.
        assert 2 * tau0 <= c['from_tau_s'] <= 0.5, (name, c)
        n = ax[wkey]
        assert n['status'] == 'measured', (name, n)
        assert abs(n['value'] / n_true - 1) < 0.03, (name, n['value'] / n_true)
        assert n['tau_range_s'][0] >= c['from_tau_s'], (name, n, c)
    assert 'short-τ end rolls off below the −½ slope' in text, text
    assert 'fitted from tau = ' in yaml, yaml


def bump_record(gen, work):
    """White noise through the low-pass filter and a Gauss-Markov bump of
    τc 0.3 s: the record of the two tests that follow (written once)."""
    out = work / 'bump'
    if (out / 'truth.json').exists():
        with open(out / 'truth.json') as f:
            return out, json.load(f)
    return record(gen, work, 'bump', 23, '--lowpass-hz', str(RATE_HZ / 8), '--gm-tau-c', '0.3',
                  '--accel-gm-sigma', '0.002', '--gyro-gm-sigma', '2e-4')


def bump_share(truth, key, i):
    """The bump's share of the true Allan variance where it is largest."""
    allan = truth['allan'][key]
    return max((b / t)**2 for b, t in zip(allan['bump'][i], allan['total'][i]))


def test_bump_measured(mpcal, gen, work):
    """The filter and the bump in the model: the bump measured on every axis,
    the truth's τc inside its interval on five of six, within 25 % where the
    bump carries at least half the variance at its peak (the gyroscope's;
    the accelerometer's carries a fifth), σ within 25 %; N within 3 % of
    the truth; the model fits from where the −½ slope begins."""
    out, truth = bump_record(gen, work)
    result, text, _ = analyse(mpcal, out)
    covered = []
    for (name, ax, wkey, n_true), (sensor, key, u) in zip(
            axes(result, truth), [s for s in SENSORS for _ in AXES]):
        i = AXES.index(name[-1])
        c = ax['model_check']
        assert c['fits'], (name, c)
        g = ax['gauss_markov']
        assert g['status'] == 'measured' and g['modelled'], (name, g)
        covered.append(g['tau_c_lo_s'] <= 0.3 <= g['tau_c_hi_s'])
        if bump_share(truth, key, i) >= 0.5:
            assert abs(g['tau_c_s'] / 0.3 - 1) < 0.25, (name, g)
        assert g['tau_c_lo_s'] <= g['tau_c_s'] <= g['tau_c_hi_s'], (name, g)
        sigma_true = truth[key]['gauss_markov_bump']['sigma_' + u][i]
        assert abs(g['sigma_' + u] / sigma_true - 1) < 0.25, (name, g, sigma_true)
        # Its share of the variance grows past its peak near 1.89 τc = 0.57 s
        # (beyond, it is white like N, and larger): read from there on.
        assert 0.1 <= g['tau_range_s'][0] <= 2.0 < g['tau_range_s'][1], (name, g)
        n = ax[wkey]
        assert n['status'] == 'measured', (name, n)
        assert abs(n['value'] / n_true - 1) < 0.03, (name, n['value'] / n_true)
        assert ax['sinusoid']['status'] == 'not_seen', (name, ax['sinusoid'])
    # A 95 % interval: the truth outside it on two axes of six would happen
    # in 3 % of records.
    assert sum(covered) >= 5, covered
    assert 'Gauss-Markov' in text and 'MISSES' not in text, text


def test_bump_left_out(mpcal, gen, work):
    """A Gauss-Markov bump (no filter) the model is told to leave out, with
    the sinusoid (the IEEE terms alone): flagged on every axis, the white
    noise not presented as measured, its bound above the truth; the table,
    the JSON and the Kalibr file say so. (With the filter too, half an hour
    is too short: the short end rolls off as far as the bump's rise within
    the curve's scatter, and the cut takes it. The study's records of 2-8 h
    flag it.)"""
    out, truth = record(gen, work, 'bump_plain', 23, '--gm-tau-c', '0.3', '--accel-gm-sigma',
                        '0.002', '--gyro-gm-sigma', '2e-4')
    result, text, yaml = analyse(mpcal, out, '--without-gauss-markov', '--without-sinusoid')
    for name, ax, wkey, n_true in axes(result, truth):
        c = ax['model_check']
        assert not c['fits'] and c['share_outside'] > 0.5, (name, c)
        # The bump peaks near 1.9 τc = 0.57 s: a run outside covers it.
        assert any(lo <= 0.57 <= hi for lo, hi in c['disagree_tau_s']), (name, c)
        n = ax[wkey]
        assert n['status'] == 'disagrees' and 'value' not in n, (name, n)
        assert n['upper_bound'] >= n_true, (name, n, n_true)
        assert ax['gauss_markov'] == {'status': 'not_seen', 'modelled': False}, (name, ax)
        assert ax['sinusoid'] == {'status': 'not_seen', 'modelled': False}, (name, ax)
    assert 'MISSES' in text and 'model misses the curve' in text, text
    assert 'NOT MEASURED: the model misses the curve' in yaml, yaml


def test_sine(mpcal, gen, work):
    """A sinusoid of period 2 s: in the model, measured on every axis with
    its period within 5 % and inside its interval, the model fits and N is
    within 3 %; told to leave it out, the check flags it on every axis near
    τ ≈ 0.37 period where its Allan deviation peaks."""
    out, truth = record(gen, work, 'sine', 24, '--sine-period', '2', '--accel-sine-amplitude', '0.003',
                        '--gyro-sine-amplitude', '3e-4')
    result, _, _ = analyse(mpcal, out)
    for name, ax, wkey, n_true in axes(result, truth):
        assert ax['model_check']['fits'], (name, ax['model_check'])
        s = ax['sinusoid']
        assert s['status'] == 'measured', (name, s)
        assert abs(s['period_s'] / 2 - 1) < 0.05, (name, s)
        assert s['period_lo_s'] <= 2 <= s['period_hi_s'], (name, s)
        n = ax[wkey]
        assert n['status'] == 'measured' and abs(n['value'] / n_true - 1) < 0.03, (name, n, n_true)
    result, _, _ = analyse(mpcal, out, '--without-sinusoid')
    for name, ax, _, _ in axes(result, truth):
        c = ax['model_check']
        assert not c['fits'], (name, c)
        assert any(lo <= 0.74 <= hi for lo, hi in c['disagree_tau_s']), (name, c)
        assert ax['sinusoid'] == {'status': 'not_seen', 'modelled': False}, (name, ax)


def region_readings(ax, u, points_per_octave=4, min_points=5, inflation=8.0):
    """N² read on N's region and on it shortened by an octave at either end,
    as docs/method.md §8 states the choice of region: what the curve's
    variance leaves when the other fitted terms are taken away, over 1/τ,
    with weights edf·(1/τ)²/(2 model²); each with its variance (the fit's
    inflation for correlated τ). Written from the method, not the code."""
    allan = ax['allan']
    c = allan['fit_avar_coefficients']
    taus, adev, edf = allan['tau_s'], allan['adev_' + u], allan['edf']
    lo, hi = ax['white_noise_%s_per_rthz' % u]['tau_range_s']
    region = [i for i, t in enumerate(taus) if lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9)]
    stretches = [region]
    if len(region) >= min_points + points_per_octave:
        stretches += [region[points_per_octave:], region[:-points_per_octave]]

    def model(t):
        return (3 * c['quantisation'] / t**2 + c['white_noise'] / t +
                2 * math.log(2) / math.pi * c['bias_instability'] + c['random_walk'] * t / 3 +
                c['rate_ramp'] * t**2 / 2)

    out = []
    for stretch in stretches:
        sw = swr = 0.0
        for i in stretch:
            t = taus[i]
            m = model(t)
            reading = (adev[i]**2 - (m - c['white_noise'] / t)) * t
            w = edf[i] / (t * t) / (2 * m * m)
            sw += w
            swr += w * reading
        out.append((swr / sw, inflation / sw))
    return c['white_noise'], out


def test_region_choice(mpcal, gen, work):
    """A weak Gauss-Markov bump the model is told to leave out, too weak for
    the check to flag on every axis: N read on its region and on that region
    shortened by an octave at either end gives readings that differ beyond
    their noise on at least one axis, and there the interval widens to hold
    them (in N², the interval's half-width is at least z times the readings'
    distance from the fit beyond their own spread)."""
    out, _ = record(gen, work, 'weak_bump', 42, '--gm-tau-c', '0.3', '--accel-gm-sigma', '0.001',
                    '--gyro-gm-sigma', '1e-4')
    result, _, _ = analyse(mpcal, out, '--without-gauss-markov', '--without-sinusoid')
    z = NormalDist().inv_cdf(0.975)
    widened = 0
    for sensor, _, u in SENSORS:
        for a in AXES:
            ax = result[sensor]['axes'][a]
            n = ax['white_noise_%s_per_rthz' % u]
            if n['status'] != 'measured':
                continue
            c, readings = region_readings(ax, u)
            excess = max(max(0.0, (r - c)**2 - v) for r, v in readings)
            widened += excess > 0
            # The interval of N², lower half (N² − lo²), against z √excess.
            assert c - n['lo']**2 >= 0.99 * z * math.sqrt(excess), (sensor, a, n, readings)
    assert widened >= 1, widened


def main():
    mpcal, root, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    gen = root / 'bench' / 'independent' / 'gen_still.py'
    tests = [v for k, v in globals().items() if k.startswith('test_')]
    for test in tests:
        test(mpcal, gen, work)
        print('ok  %s' % test.__name__)
    print('%d tests passed' % len(tests))
    return 0


if __name__ == '__main__':
    sys.exit(main())
