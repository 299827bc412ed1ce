"""The Cramér-Rao bound of the gyroscope matrix M for a session of gen_imu_session.py,
from the generator's own truth and noise figures (not from mpcal).

The measurement model is the one the turn-residual estimator uses:
for each turn k from static position k to k+1, the gravity direction measured
at the end of position k, carried over the turn by the gyroscope,
    R_k(M) = prod_i Exp(phi_i),  phi_i = (M r_i + M r_i+1)/2 dt + (M r_i dt x M r_i+1 dt)/12,
with r_i the bias-free raw readings, is compared with the direction measured
at the start of position k+1: a 2-D tilt residual e_k = B_k^T (R_k^T u_from - u_to),
B_k an orthonormal basis of the plane perpendicular to u_to.  Its noise, from
the generator's true figures (per tangent component, rad^2):
  - the gyroscope's white noise integrated over the turn: sigma_g^2 dt T;
  - the bias measured as the mean of each position (n_k samples), interpolated
    linearly across the turn: T^2 ((1-l)^2 sigma_g^2/n_k + l^2 sigma_g^2/n_k+1);
  - the bias's random walk (density K) left by that interpolation: the integral
    over the turn of a Brownian bridge between the two positions' centres;
  - the two directions, each the mean accelerometer reading over WINDOW_S at
    the position's edge (mpcal's direction window): sigma_a^2 / (n_w g^2);
  - the file's rounding (one count, or the last printed decimal) in both sensors;
all gyroscope terms scaled by mean(diag(M M^T)).  The Fisher information is
sum_k J_k^T J_k / sigma_k^2 with J_k = d e_k / d M (row-major, 2 x 9) at the
truth, by central differences of the integration above applied to the
generator's noise-free body rate (r_i = M^-1 w_ib,i); the bound is its inverse.
"""
import math

import numpy as np

import so3

WINDOW_S = 1.0  # mpcal's GyroOptions::direction_window_s (the directions' averaging time)
STEP = 1e-6     # central-difference step on the entries of M


def _turns(sim):
    return [s for s in sim['segs'] if s['kind'] == 'turn']


def _statics(sim):
    return [s for s in sim['segs'] if s['kind'] == 'static']


def _carry(sim, turns, ms):
    """Directions carried over every turn for every matrix in `ms` (V x 3 x 3):
    array (V, turns, 3) of R^T u_from, and u_from, u_to (turns x 3)."""
    dt = 1.0 / sim['rate']
    m_true_inv = np.linalg.inv(np.asarray(sim['gyro']['M']))
    raw = sim['w_ib'] @ m_true_inv.T  # bias-free raw readings, noise free (rad/s)
    n = max(s['i1'] - s['i0'] for s in turns)
    v, t = len(ms), len(turns)
    q = np.tile([1.0, 0.0, 0.0, 0.0], (v * t, 1))
    for m in range(n):
        active = np.array([s['i0'] + m < s['i1'] for s in turns])
        idx = np.array([min(s['i0'] + m, s['i1'] - 1) for s in turns])
        a = np.einsum('vij,tj->vti', ms, raw[idx]) * dt
        b = np.einsum('vij,tj->vti', ms, raw[idx + 1]) * dt
        theta = (a + b) / 2 + np.cross(a, b) / 12
        theta[:, ~active] = 0
        q = so3.mul(q, so3.exp(theta.reshape(v * t, 3)))
    # the gravity direction (world up) in the body frame at both ends: the
    # specific force there also holds the tremor's lever-arm acceleration,
    # which the accelerometer's mean over the direction window averages out
    up = np.array([0.0, 0.0, 1.0])
    u_from = so3.rotate_inv(np.array([sim['q'][s['i0']] for s in turns]), np.tile(up, (len(turns), 1)))
    u_to = so3.rotate_inv(np.array([sim['q'][s['i1']] for s in turns]), np.tile(up, (len(turns), 1)))
    carried = so3.rotate_inv(q, np.tile(u_from, (v, 1))).reshape(v, t, 3)
    return carried, u_from, u_to


def _basis(u):
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    return np.stack([e1, np.cross(u, e1)], axis=1)  # 3 x 2


def _bridge_integral(t_a, t_b, s0, s1, points=64):
    """Var of the integral over [s0, s1] of a unit Brownian bridge pinned at t_a and t_b."""
    span = t_b - t_a
    s = np.linspace(s0, s1, points) - t_a
    s = np.clip(s, 0.0, span)
    c = np.minimum.outer(s, s) - np.outer(s, s) / span
    h = (s1 - s0) / (points - 1)
    w = np.full(points, h)
    w[0] = w[-1] = h / 2
    return float(w @ c @ w)


def _lsb_var(truth, key, units):
    step = truth['log'][key] if truth['log'][units] == 'counts' else 1e-5 * truth['log'][key]
    return step * step / 12


def turn_variances(sim, truth):
    """Per turn, the variance (rad^2) of each tangent component of its residual."""
    rate = sim['rate']
    dt = 1.0 / rate
    m = np.asarray(sim['gyro']['M'])
    gain = float(np.mean(np.diag(m @ m.T)))
    var_g = sim['gyro']['sigma_per_sample_radps']**2 + _lsb_var(truth, 'gyro_si_per_unit', 'gyro_units')
    var_a = sim['acc']['sigma_per_sample_mps2']**2 + _lsb_var(truth, 'accel_si_per_unit', 'accel_units')
    k_rw = sim['gyro']['random_walk_radps2_per_sqrt_hz']
    n_w = WINDOW_S * rate
    statics = _statics(sim)
    out = []
    for s in _turns(sim):
        a, b = statics[s['k']], statics[s['k'] + 1]
        n_a, n_b = a['i1'] - a['i0'] + 1, b['i1'] - b['i0'] + 1
        c_a, c_b = (a['i0'] + a['i1']) / 2 * dt, (b['i0'] + b['i1']) / 2 * dt
        t0, t1 = s['i0'] * dt, s['i1'] * dt
        dur = t1 - t0
        lam = ((t0 + t1) / 2 - c_a) / (c_b - c_a)
        white = var_g * dt * dur
        bias = dur * dur * ((1 - lam)**2 * var_g / n_a + lam**2 * var_g / n_b)
        walk = k_rw * k_rw * _bridge_integral(c_a, c_b, t0, t1)
        direction = 2 * var_a / (n_w * sim['gravity']**2)
        out.append(gain * (white + bias + walk) + direction)
    return np.array(out)


def gyro_bound(sim, truth):
    """The 9 x 9 Cramér-Rao bound of M (row-major) for this session."""
    turns = _turns(sim)
    m0 = np.asarray(sim['gyro']['M'], dtype=float)
    ms = [m0]
    for p in range(9):
        for sign in (1.0, -1.0):
            d = np.zeros(9)
            d[p] = sign * STEP
            ms.append(m0 + d.reshape(3, 3))
    carried, _, u_to = _carry(sim, turns, np.array(ms))
    var = turn_variances(sim, truth)
    info = np.zeros((9, 9))
    for k in range(len(turns)):
        basis = _basis(u_to[k])
        jac = np.stack([basis.T @ (carried[1 + 2 * p, k] - carried[2 + 2 * p, k]) / (2 * STEP)
                        for p in range(9)], axis=1)  # 2 x 9
        info += jac.T @ jac / var[k]
    return np.linalg.inv(info)


def with_detected_segments(sim, intervals):
    """A view of `sim` whose static positions are the intervals a detector
    found (mpcal detect --json: begin, end one past, in samples) and whose
    turns join them, from the last sample of one to the first of the next:
    the segments an estimator that finds the positions from the data works
    on. The bound on these is the bound given that segmentation."""
    segs = []
    for k, iv in enumerate(intervals):
        segs.append({'kind': 'static', 'k': k, 'i0': iv['begin'], 'i1': iv['end'] - 1})
        if k + 1 < len(intervals):
            segs.append({'kind': 'turn', 'k': k, 'i0': iv['end'] - 1, 'i1': intervals[k + 1]['begin']})
    view = dict(sim)
    view['segs'] = segs
    return view


def residual_rms_deg(sim):
    """RMS tilt (deg) of the noise-free integration at the truth: the scheme's own error."""
    turns = _turns(sim)
    carried, _, u_to = _carry(sim, turns, np.array([np.asarray(sim['gyro']['M'], dtype=float)]))
    tilt = np.linalg.norm(np.cross(carried[0], u_to), axis=1)
    return math.degrees(float(np.sqrt(np.mean(tilt**2))))
