#!/usr/bin/env python3
"""Where the turn residuals' variance comes from, at the true M (no mpcal).

For sessions of gen_imu_session.py (simulated in memory, no file), each turn's
2-D tilt residual is formed as the turn-residual estimator forms it (issue
17): the bias is the mean gyroscope reading of each static position,
interpolated linearly in time between the positions' centres; the gyroscope
readings minus that bias, times the TRUE M, are integrated over the turn;
the gravity directions are the means of the accelerometer over the last
(first) WINDOW_S of the positions, corrected with the TRUE accelerometer
parameters.  The residual is split into the parts of each disturbance by
replaying it with one part at a time:

  white    the gyroscope's white noise (with the static means' noise)
  walk     the bias's random walk left by the linear interpolation
  earth    the Earth rate's projection changing during the turn
  dirs     the accelerometer's white noise in the two directions

and each part's mean square over the turns is compared with the variance
that gyro_bound.turn_variances gives it (and mpcal's weights before the walk
was added to them: white + dirs).
Prints, per part, mean(r^2)/mean(model var) (1.0: the model holds that
part), and chi2/dof of the full residual under both models.

  gyro_noise_budget.py [--sessions N] [--seed-base S] [--tremor T]
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from _numpy import need_numpy  # noqa: E402

need_numpy()
import numpy as np  # noqa: E402

import gen_imu_session  # noqa: E402
import gyro_bound  # noqa: E402
import so3  # noqa: E402


def carry_many(sim, jobs):
    """2-D residuals of many (turn, raw, bias_a, bias_b, c_a, c_b, u_from, u_to)
    jobs at once: bias interpolated, integrated with the true M."""
    dt = 1.0 / sim['rate']
    m = np.asarray(sim['gyro']['M'])
    n = max(s['i1'] - s['i0'] for s, *_ in jobs)
    theta = np.zeros((len(jobs), n, 3))
    for j, (s, raw, ba, bb, c_a, c_b, _, _) in enumerate(jobs):
        idx = np.arange(s['i0'], s['i1'] + 1)
        lam = np.clip((idx * dt - c_a) / (c_b - c_a), 0.0, 1.0)[:, None]
        w = (raw[idx] - ((1 - lam) * ba + lam * bb)) @ m.T
        a, b = w[:-1] * dt, w[1:] * dt
        theta[j, :len(a)] = (a + b) / 2 + np.cross(a, b) / 12
    q = np.tile([1.0, 0.0, 0.0, 0.0], (len(jobs), 1))
    for i in range(n):
        q = so3.mul(q, so3.exp(theta[:, i]))
    u_from = np.array([job[6] for job in jobs])
    carried = so3.rotate_inv(q, u_from)
    return np.array([gyro_bound._basis(job[7]).T @ c for job, c in zip(jobs, carried)])


def accel_correct(sim, y):
    acc = sim['acc']
    tm = gen_imu_session.t_matrix(acc['theta']['yz'], acc['theta']['zx'], acc['theta']['zy'])
    return ((y - np.array(acc['bias_mps2'])) / (1 + np.array(acc['sfe']))) @ tm.T


def session_parts(sim):
    """Per turn: residual with everything, and with each part alone."""
    rate = sim['rate']
    dt = 1.0 / rate
    nw = int(round(gyro_bound.WINDOW_S * rate))
    statics = gyro_bound._statics(sim)
    turns = gyro_bound._turns(sim)
    minv = np.linalg.inv(np.asarray(sim['gyro']['M']))
    ideal = sim['w'] @ minv.T                     # motion only
    earth = (sim['w_ib'] - sim['w']) @ minv.T     # Earth rate only
    walk = sim['bias'] - sim['bias'][0]           # bias walk only
    white = sim['y_gyro'] - sim['g_clean']        # white noise only
    up = np.array([0.0, 0.0, 1.0])
    true_up = so3.rotate_inv(sim['q'], np.tile(up, (len(sim['t']), 1)))
    acc = accel_correct(sim, sim['y_acc'])
    variants = {'all': ideal + earth + walk + white, 'white': ideal + white,
                'walk': ideal + walk, 'earth': ideal + earth, 'dirs': ideal}
    jobs, names = [], []
    for s in turns:
        a, b = statics[s['k']], statics[s['k'] + 1]
        c_a, c_b = (a['i0'] + a['i1']) / 2 * dt, (b['i0'] + b['i1']) / 2 * dt
        u_from_m = acc[a['i1'] - nw + 1:a['i1'] + 1].mean(axis=0)
        u_to_m = acc[b['i0']:b['i0'] + nw].mean(axis=0)
        u_from_m /= np.linalg.norm(u_from_m)
        u_to_m /= np.linalg.norm(u_to_m)
        for name, raw in variants.items():
            if name in ('all', 'dirs'):
                uf, ut = u_from_m, u_to_m
            else:
                uf, ut = true_up[s['i0']], true_up[s['i1']]
            ba = raw[a['i0']:a['i1'] + 1].mean(axis=0)
            bb = raw[b['i0']:b['i1'] + 1].mean(axis=0)
            jobs.append((s, raw, ba, bb, c_a, c_b, uf, ut))
            names.append(name)
    res = carry_many(sim, jobs)
    return {k: np.array([r for r, nm in zip(res, names) if nm == k]) for k in variants}


def model_parts(sim, truth):
    """Per turn, the bound's variance of each part (per tangent component)."""
    saved = dict(sim['gyro'])
    parts = {}
    full = gyro_bound.turn_variances(sim, truth)
    sim['gyro']['random_walk_radps2_per_sqrt_hz'] = 0.0
    no_walk = gyro_bound.turn_variances(sim, truth)
    sim['gyro']['sigma_per_sample_radps'] = 0.0
    dirs = gyro_bound.turn_variances(sim, truth)
    sim['gyro'].update(saved)
    parts['all'] = full
    parts['walk'] = full - no_walk
    parts['white'] = no_walk - dirs
    parts['dirs'] = dirs
    parts['mpcal'] = no_walk  # mpcal's weights before gyrobound: no walk
    return parts


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--sessions', type=int, default=10)
    ap.add_argument('--seed-base', type=int, default=1000)
    ap.add_argument('--tremor', type=float, default=0.0)
    args = ap.parse_args()
    acc = {}
    for i in range(args.sessions):
        seed = args.seed_base + i + 1
        ga = gen_imu_session.parse_args(['--out', '/nonexistent', '--seed', str(seed),
                                         '--tremor', str(args.tremor)])
        sim = gen_imu_session.simulate(ga)
        truth = {'log': {'gyro_units': 'rads', 'accel_units': 'mps2',
                         'gyro_si_per_unit': 1.0, 'accel_si_per_unit': 1.0}}
        r = session_parts(sim)
        v = model_parts(sim, truth)
        for name, res in r.items():
            acc.setdefault(name, []).append(np.mean(res**2, axis=1))
        for name, var in v.items():
            acc.setdefault('var_' + name, []).append(var)
    cat = {k: np.concatenate(v) for k, v in acc.items()}
    print('%d sessions, %d turns, tremor %g' % (args.sessions, len(cat['all']), args.tremor))
    for name in ('white', 'walk', 'earth', 'dirs'):
        model = cat.get('var_' + name)
        ratio = np.mean(cat[name]) / np.mean(model) if model is not None else float('nan')
        print('%-6s mean r^2 %.3e  bound var %s  ratio %s' % (
            name, np.mean(cat[name]), '%.3e' % np.mean(model) if model is not None else '   -     ',
            '%.3f' % ratio if model is not None else '  -'))
    print('all: chi2/dof under the bound\'s variances %.3f, without the walk %.3f'
          % (np.mean(cat['all'] / cat['var_all']), np.mean(cat['all'] / cat['var_mpcal'])))


if __name__ == '__main__':
    sys.exit(main())
