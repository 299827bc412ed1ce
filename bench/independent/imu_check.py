"""The self-checks of gen_imu_session.py --check (see its docstring).

(a) the closed-form body rate integrates (RK4, sub-steps) to the closed-form
    attitude at the end of every turn;
(b) session.csv read back, omega = M (raw - b_g) - R^T Omega_E integrated over
    each turn carries the gravity direction of position k onto that of k+1
    within the gyroscope noise;
(c) the static means of the file's accelerometer (corrected with the true
    parameters) and gyroscope equal the truth's noise-free means within noise.
Statistics are chi-square over all turns / positions, accepted between the
0.1 % and 99.9 % points.
"""
import math
import os

import numpy as np

import so3

RK4_MAX_STEP_S = 1.0 / 1600
EXACT_TOLERANCE_RAD = 1e-8


def chi2_bounds(dof, z=3.09):
    """0.1 % and 99.9 % points of chi-square (Wilson-Hilferty)."""
    c = 2.0 / (9 * dof)
    return tuple(dof * (1 - c + s * z * math.sqrt(c))**3 for s in (-1, 1))


def turns_of(sim):
    return [s for s in sim['segs'] if s['kind'] == 'turn']


def substeps(rate):
    return max(8, math.ceil(1 / (rate * RK4_MAX_STEP_S)))


def rk4_turns(sim):
    """Max angle (rad) between the RK4-integrated and the closed-form attitude at turn ends."""
    turns = turns_of(sim)
    rate = sim['rate']
    sub = substeps(rate)
    h = 1.0 / (rate * sub)
    steps = [(s['i1'] - s['i0']) * sub for s in turns]
    smax = max(steps)
    w = np.zeros((len(turns), 2 * smax + 1, 3))
    for j, s in enumerate(turns):
        t = s['i0'] / rate + np.arange(2 * steps[j] + 1) * (h / 2)
        w[j, :len(t)] = sim['motion'].state(t)[1]
    q = np.array([sim['q'][s['i0']] for s in turns])

    def f(q, wk):
        return 0.5 * so3.mul(q, np.concatenate([np.zeros((len(q), 1)), wk], axis=1))
    for m in range(smax):
        w0, wm, w1 = w[:, 2 * m], w[:, 2 * m + 1], w[:, 2 * m + 2]
        k1 = f(q, w0)
        k2 = f(q + h / 2 * k1, wm)
        k3 = f(q + h / 2 * k2, wm)
        k4 = f(q + h * k3, w1)
        active = (m < np.array(steps))[:, None]  # a finished turn keeps its end attitude
        q = np.where(active, q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), q)
        q /= np.linalg.norm(q, axis=1, keepdims=True)
    return max(so3.angle_between(q[j], sim['q'][s['i1']]) for j, s in enumerate(turns))


def strapdown_turns(sim, w_ib):
    """Attitude at each turn's end from the true one at its start, integrating
    w_ib - R^T Omega_E per sample (trapezoid + coning term)."""
    turns = turns_of(sim)
    dt = 1.0 / sim['rate']
    n = max(s['i1'] - s['i0'] for s in turns)
    q = np.array([sim['q'][s['i0']] for s in turns])
    for m in range(n):
        active = np.array([s['i0'] + m < s['i1'] for s in turns])
        idx = np.array([min(s['i0'] + m, s['i1'] - 1) for s in turns])
        wa = w_ib[idx] - so3.rotate_inv(q, np.tile(sim['omega_e'], (len(turns), 1)))
        wb = w_ib[idx + 1] - so3.rotate_inv(q, np.tile(sim['omega_e'], (len(turns), 1)))
        theta = (wa + wb) / 2 * dt + np.cross(wa, wb) * dt * dt / 12
        theta[~active] = 0
        q = so3.mul(q, so3.exp(theta))
    return q


def tilt_errors(sim, q_end):
    """Per turn, the tilt of the predicted body up direction from the true one (rad)."""
    turns = turns_of(sim)
    z = np.tile([0.0, 0.0, 1.0], (len(turns), 1))
    u_true = so3.rotate_inv(np.array([sim['q'][s['i1']] for s in turns]), z)
    u_pred = so3.rotate_inv(q_end, z)
    return np.linalg.norm(np.cross(u_true, u_pred), axis=1)


def read_log(out_dir, truth):
    data = np.loadtxt(os.path.join(out_dir, truth['log']['file']), delimiter=',', skiprows=1)
    return (data[:, 1:4] * truth['log']['accel_si_per_unit'],
            data[:, 4:7] * truth['log']['gyro_si_per_unit'])


def lsb_var(truth, key, units):
    """Variance added by the file's rounding (counts: one LSB; text: the last decimal)."""
    step = truth['log'][key] if truth['log'][units] == 'counts' else 1e-5 * truth['log'][key]
    return step * step / 12


def gyro_turn_check(sim, truth, gyro_si):
    m = np.array(truth['gyroscope']['M']).reshape(3, 3)
    noisy = (gyro_si - sim['bias']) @ m.T
    # the sampling error of the scheme alone: the true rate at the samples
    clean = sim['w_ib']
    tilt = tilt_errors(sim, strapdown_turns(sim, noisy))
    tilt_disc = tilt_errors(sim, strapdown_turns(sim, clean))
    dur = np.array([(s['i1'] - s['i0']) / sim['rate'] for s in turns_of(sim)])
    var_rate = sim['gyro']['sigma_per_sample_radps']**2 + lsb_var(truth, 'gyro_si_per_unit', 'gyro_units')
    # noise (white, and the file's rounding) plus the sampling error of the scheme itself
    # (an error budget: about 0.1 sigma at 200 Hz, comparable to it at 50 Hz)
    sigma = np.sqrt(var_rate / sim['rate'] * dur * np.mean(np.diag(m @ m.T)) + tilt_disc**2)
    chi2 = float(np.sum((tilt / sigma)**2))
    return tilt, tilt_disc, sigma, chi2


def static_means_check(sim, truth, acc_si, gyro_si):
    acc = truth['accelerometer']
    tm = _t_matrix(acc['theta'])
    c = tm @ np.diag(1 / (1 + np.array(acc['sfe'])))
    a = (acc_si - np.array(acc['bias_mps2'])) @ c.T
    va = sim['acc']['sigma_per_sample_mps2']**2 + lsb_var(truth, 'accel_si_per_unit', 'accel_units')
    vg = sim['gyro']['sigma_per_sample_radps']**2 + lsb_var(truth, 'gyro_si_per_unit', 'gyro_units')
    chi_a = chi_g = 0.0
    worst_norm = 0.0
    for st in truth['static_intervals']:
        i0 = int(round(st['start_s'] * sim['rate']))
        sl = slice(i0, i0 + st['samples'])
        n = st['samples']
        da = a[sl].mean(axis=0) - np.array(st['specific_force_mean_body_mps2'])
        chi_a += float(da @ np.linalg.solve(c @ c.T * va / n, da))
        dg = gyro_si[sl].mean(axis=0) - np.array(st['gyro_raw_mean_noise_free_radps'])
        chi_g += float(dg @ dg) / (vg / n)
        worst_norm = max(worst_norm, abs(np.linalg.norm(a[sl].mean(axis=0)) - truth['gravity_mps2']))
    return chi_a, chi_g, 3 * len(truth['static_intervals']), worst_norm


def _t_matrix(theta):
    tyz, tzx, tzy = theta['yz'], theta['zx'], theta['zy']
    return np.array([
        [1.0, 0.0, 0.0],
        [math.tan(tyz), 1 / math.cos(tyz), 0.0],
        [math.tan(tzx) * math.tan(tyz) - math.tan(tzy) / math.cos(tzx),
         math.tan(tzx) / math.cos(tyz), 1 / (math.cos(tzx) * math.cos(tzy))]])


def run(sim, out_dir, truth):
    ok = True

    def verdict(name, passed, text):
        nonlocal ok
        ok &= bool(passed)
        print('check %s: %s  %s' % (name, 'ok' if passed else 'FAILED', text))

    exact = rk4_turns(sim)
    verdict('(a) closed-form rate -> attitude', exact < EXACT_TOLERANCE_RAD,
            'max angle at turn ends %.2e rad (RK4, %d sub-steps; bar %.0e)'
            % (exact, substeps(sim['rate']), EXACT_TOLERANCE_RAD))
    acc_si, gyro_si = read_log(out_dir, truth)
    tilt, tilt_disc, sigma, chi2 = gyro_turn_check(sim, truth, gyro_si)
    lo, hi = chi2_bounds(2 * len(tilt))
    verdict('(b) gyro carries gravity k -> k+1', lo <= chi2 <= hi and np.all(tilt < 5 * sigma),
            'tilt RMS %.4f deg, max %.4f deg (%.1f sigma); 1-sigma per axis %.4f-%.4f deg; '
            'chi2 %.1f for %d dof (%.1f-%.1f); sampling alone: max %.5f deg'
            % (math.degrees(np.sqrt(np.mean(tilt**2))), math.degrees(tilt.max()), np.max(tilt / sigma),
               math.degrees(sigma.min()), math.degrees(sigma.max()), chi2, 2 * len(tilt), lo, hi,
               math.degrees(tilt_disc.max())))
    chi_a, chi_g, dof, worst_norm = static_means_check(sim, truth, acc_si, gyro_si)
    lo, hi = chi2_bounds(dof)
    verdict('(c) static means', lo <= chi_a <= hi and lo <= chi_g <= hi,
            'accelerometer chi2 %.1f, gyroscope chi2 %.1f for %d dof (%.1f-%.1f); '
            'max ||a|-g| of a corrected mean %.2e m/s^2' % (chi_a, chi_g, dof, lo, hi, worst_norm))
    return ok
