#!/usr/bin/env python3
"""Independent hand-held multi-position IMU session: accelerometer + gyroscope.

Written from docs/method.md §2 and §7 and the README's log format, without
reading mpcal's simulator or estimators, so that studies can test mpcal's
accelerometer and gyroscope calibration on data its authors did not make.

  gen_imu_session.py --out DIR --seed S [--positions N] [--rate HZ]
                     [--accel-units mps2|g|counts] [--gyro-units rads|dps|counts]
                     [--earth-rate on|off] [--latitude DEG] [--lever-arm M]
                     [--tremor SCALE] [--check]

writes DIR/session.csv and DIR/truth.json; the same arguments always give the
same files. Example:

  gen_imu_session.py --out /tmp/s1 --seed 1 --gyro-units dps --check

CONVENTIONS (everything SI inside; the file's units are chosen by the options)

Frames.
  World W: local level, x east, y north, z up; fixed to the Earth.
  Body B: the accelerometer's orthogonalised frame, the frame in which the
    corrected specific force a of docs/method.md §2 is expressed: x along
    the accelerometer's x axis, y in the plane of its x and y axes, z
    completing a right-handed triad.
  Attitude: R = R_world_body maps body coordinates to world, v_W = R v_B.
    The quaternion q (Hamilton, scalar first [w, x, y, z]) is the same
    rotation: v_W = q (0, v_B) q*.
  Body angular rate omega (rad/s, body frame, motion relative to W):
    dR/dt = R [omega]x,  dq/dt = 1/2 q (0, omega).

Motion.  N static positions (default 26-40 drawn from the seed): the 26
  directions of a cube (6 faces, 12 edges, 8 corners; repeated when N > 26)
  as the body-frame "up" (specific-force direction), each tilted by hand
  jitter of 0.5-5 deg and given a yaw about world z; the first one is z up and
  held 20-40 s (the initial rest), the others 5-40 s.  Consecutive positions
  are joined by turns of 1-4 s.  The attitude in closed form is
      q(t) = q_nom(t) * Exp(v_turn(t)) * Exp(v_tremor(t))
  q_nom: the position's attitude q_k while static; in a turn from k to k+1,
    q_k * Exp(s(x) phi), phi = Log(q_k* q_k+1), x = (t - t0)/duration,
    s a minimum-jerk profile in a skewed time x^p (p 0.8-1.25): bell-shaped
    rate, zero rate and zero angular acceleration at both ends.
  v_turn (only in turns): 64 x^3 (1-x)^3 [A1 e1 + A2 sin(2 pi f2 (t-t0) + p2) e2]:
    a swing of 10-45 % of the turn angle about an axis perpendicular to phi
    and a 2-8 deg hand correction at 0.7-2.5 Hz about a random axis, so the
    rotation axis wanders during the turn (turns are not about one axis).
  v_tremor (always, scaled by --tremor): two sway terms 0.1-0.6 Hz,
    0.02-0.15 deg; two hand terms 1-4 Hz, 0.005-0.03 deg; physiological
    8-12 Hz, 0.002-0.01 deg; each about a fixed random axis.
  Exp/Log are the SO(3) exponential and logarithm of rotation vectors, and
  the body rate is exact: for q = A B C, omega = R_C^T (R_B^T w_A + w_B) + w_C,
  w of Exp(v(t)) being J_r(v) dv/dt (right Jacobian).  --check integrates
  this omega with fine RK4 sub-steps and recovers the closed-form attitude.
  Translation: in a turn the hand lifts the device by 2-10 cm and slides it
  up to 15 cm (minimum-jerk), and the sensor sits at a lever arm r (body
  frame, |r| = --lever-arm, default 0.05 m) from the centre of rotation, so
      f_B = R^T (p_hand'' + G z_W) + domega/dt x r + omega x (omega x r).

Accelerometer (docs/method.md §2):
      Y = b + diag(1 + s) T^-1 f_B + n_a        (m/s^2)
  b up to 0.15 g, s up to 6 %, angles up to 0.02 rad; n_a white, per-sample
  sigma = N_a sqrt(rate) with the density N_a 0.0008-0.004 m/s^2/sqrt(Hz).
Gyroscope:
      raw = M^-1 (omega + R^T Omega_E) + b_g(t) + n_g   (rad/s)
  so that omega + R^T Omega_E = M (raw - b_g).  M general 3x3: diagonal
  1 +- 6 %, off-diagonal +-0.03 rad; b_g(0) up to 3 deg/s per axis, then a
  random walk with increments K sqrt(1/rate) (K 1e-5 - 6e-5 rad/s^2/sqrt(Hz));
  n_g white of density N_g 0.004-0.015 deg/s/sqrt(Hz) (sigma N_g sqrt(rate)).
  Omega_E = 7.292115e-5 rad/s (0, cos lat, sin lat) in W (--earth-rate on,
  the default; latitude drawn in +-60 deg unless --latitude).  A static mean
  of raw therefore holds b_g + M^-1 R^T Omega_E (+ the mean tremor rate).
Samples are instantaneous values at t_i = i / rate; no range limit except
in counts (int16, clipped; the clipped count is in the truth).

Files.
  session.csv: header t,ax,ay,az,gx,gy,gz; t in s; accelerometer in m/s^2
    (mps2), g (9.80665 m/s^2) or int16 counts (8192 per g, zero 0);
    gyroscope in rad/s (rads), deg/s (dps) or int16 counts (16.4 per deg/s).
    mpcal reads mps2/g/counts and rads/dps; truth.json "log.mpcal_options"
    names the options.  Gyroscope counts are for other tools.
  truth.json: "accelerometer" (bias_mps2, sfe, theta {yz, zx, zy} as
    gen_session.py writes them, noise), "gyroscope" (M row-major with
    omega = M (raw - b), its inverse, bias at 0, K, N, Earth rate in W),
    "static_intervals" (start/end s, attitude quaternions at both ends, mean
    body up direction, mean true specific force, gyroscope bias at start, end
    and mean, expected noise-free raw gyroscope mean, cube target) and
    "turns" (start/end s, net angle and axis in the body frame at the start,
    nominal angle, path angle, peak rate).  All boundaries are on samples.

--check (after writing): (a) integrating the true omega with 16 RK4
  sub-steps per sample gives the closed-form attitude at the end of every
  turn; (b) reading session.csv back, omega = M (raw - b_g) - R^T Omega_E
  integrated over each turn (trapezoid + coning correction) carries the
  gravity direction of position k to that of k+1 within the gyroscope
  noise (chi-square of the tilt residuals at 0.1 %); (c) the static means of
  the accelerometer corrected with the true parameters equal the true mean
  specific force within the noise.  Prints a summary; exit 1 on failure.
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
import imu_check  # noqa: E402
import so3  # noqa: E402

G_STD = 9.80665
EARTH_RATE_RADPS = 7.292115e-5
DEG = math.pi / 180
ACCEL_COUNTS_PER_G = 8192.0     # +-4 g, int16
GYRO_COUNTS_PER_DPS = 16.4      # +-2000 deg/s, int16
FORMAT = 'mpcal.independent.imu_session/1'


# ---------------------------------------------------------------- profiles
def minjerk(x):
    return x**3 * (10 - 15 * x + 6 * x * x)


def minjerk_d(x):
    return 30 * x * x * (1 - x)**2


def minjerk_dd(x):
    return 60 * x * (1 - x) * (1 - 2 * x)


def bump(x):      # 64 x^3 (1-x)^3: 0 at both ends with two derivatives, 1 at x = 0.5
    return 64 * x**3 * (1 - x)**3


def bump_d(x):
    return 192 * x * x * (1 - x)**2 * (1 - 2 * x)


def bump_dd(x):
    return 384 * x * (1 - x) * ((1 - 2 * x)**2 - x * (1 - x))


# ---------------------------------------------------------------- error models
def t_matrix(tyz, tzx, tzy):
    """docs/method.md §2: a = T diag(1/(1+s)) (Y - b)."""
    return np.array([
        [1.0, 0.0, 0.0],
        [math.tan(tyz), 1 / math.cos(tyz), 0.0],
        [math.tan(tzx) * math.tan(tyz) - math.tan(tzy) / math.cos(tzx),
         math.tan(tzx) / math.cos(tyz), 1 / (math.cos(tzx) * math.cos(tzy))]])


def draw_sensor(rng, rate_hz):
    acc = {'bias_mps2': list(rng.uniform(-0.15, 0.15, 3) * G_STD),
           'sfe': list(rng.uniform(-0.06, 0.06, 3)),
           'theta': dict(zip(('yz', 'zx', 'zy'), rng.uniform(-0.02, 0.02, 3)))}
    acc['noise_density_mps2_per_sqrt_hz'] = float(rng.uniform(0.0008, 0.004))
    m = np.diag(1 + rng.uniform(-0.06, 0.06, 3))
    off = ~np.eye(3, dtype=bool)
    m[off] = rng.uniform(-0.03, 0.03, 6)
    gyro = {'M': m,
            'bias0_radps': rng.uniform(-3, 3, 3) * DEG,
            'random_walk_radps2_per_sqrt_hz': float(math.exp(rng.uniform(math.log(1e-5), math.log(6e-5)))),
            'noise_density_radps_per_sqrt_hz': float(rng.uniform(0.004, 0.015) * DEG)}
    acc['sigma_per_sample_mps2'] = acc['noise_density_mps2_per_sqrt_hz'] * math.sqrt(rate_hz)
    gyro['sigma_per_sample_radps'] = gyro['noise_density_radps_per_sqrt_hz'] * math.sqrt(rate_hz)
    return acc, gyro


# ---------------------------------------------------------------- positions
def cube_targets():
    out = []
    for x in (-1, 0, 1):
        for y in (-1, 0, 1):
            for z in (-1, 0, 1):
                nz = abs(x) + abs(y) + abs(z)
                if nz:
                    out.append(((x, y, z), {1: 'face', 2: 'edge', 3: 'corner'}[nz]))
    return out


def tilt(rng, u, max_deg):
    p = np.cross(u, so3.random_unit(rng))
    p /= np.linalg.norm(p)
    return so3.rotate(so3.exp(p * rng.uniform(0.5, max_deg) * DEG), u)


def angle_deg(u, v):
    return math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(u, v))))))


def order_targets(rng, n):
    """Position 0 z up; then cube directions in a hand-like order (the next
    one 30-120 deg from the last when possible)."""
    cube = cube_targets()
    pool = [cube[i] for i in rng.permutation(len(cube))]
    while len(pool) < n - 1:
        pool += [cube[i] for i in rng.permutation(len(cube))]
    pool = pool[:n - 1]
    seq = [((0, 0, 1), 'face')]
    while pool:
        last = np.array(seq[-1][0], float) / np.linalg.norm(seq[-1][0])
        angles = [angle_deg(last, np.array(d, float) / np.linalg.norm(d)) for d, _ in pool]
        good = [i for i, a in enumerate(angles) if 30 <= a <= 120]
        fair = [i for i, a in enumerate(angles) if a >= 20]
        pick = good or fair or list(range(len(pool)))
        seq.append(pool.pop(pick[rng.integers(len(pick))]))
    return seq


def attitude_for_up(u, yaw):
    """q (body->world) whose body-frame up direction u maps to world z, then yaw about z."""
    return so3.mul(so3.exp(np.array([0, 0, yaw])), so3.from_to(u, np.array([0.0, 0.0, 1.0])))


def place_positions(rng, n):
    targets = order_targets(rng, n)
    positions = []
    for k, (d, kind) in enumerate(targets):
        u = tilt(rng, np.array(d, float) / np.linalg.norm(d), 5.0)
        if k == 0:
            q = attitude_for_up(u, rng.uniform(0, 2 * math.pi))
        else:
            prev = positions[-1]['q']
            yaws = np.linspace(0, 2 * math.pi, 360, endpoint=False)
            angs = [so3.angle_between(prev, attitude_for_up(u, y)) for y in yaws]
            best = yaws[int(np.argmin(angs))]
            for _ in range(50):  # a yaw near the shortest turn, so that turns are about varied axes
                q = attitude_for_up(u, best + rng.normal(0, 25 * DEG))
                if so3.angle_between(prev, q) < 170 * DEG:
                    break
        positions.append({'q': q, 'target': list(d), 'kind': kind})
    return positions


# ---------------------------------------------------------------- timeline
def build_timeline(rng, positions, rate_hz):
    """Static and turn segments with boundaries on the sample grid (times in samples)."""
    typical_dwell = rng.uniform(8, 30)
    segs = []
    i = 0
    for k, pos in enumerate(positions):
        dwell = rng.uniform(20, 40) if k == 0 else float(np.clip(typical_dwell * rng.uniform(0.6, 1.4), 5, 40))
        n = int(round(dwell * rate_hz))
        segs.append({'kind': 'static', 'k': k, 'i0': i, 'i1': i + n, 'q': pos['q']})
        i += n
        if k + 1 == len(positions):
            break
        qa, qb = pos['q'], positions[k + 1]['q']
        phi = so3.log(so3.mul(so3.conj(qa), qb))
        ang = float(np.linalg.norm(phi))
        dur = float(np.clip(0.9 + math.degrees(ang) / 90 * rng.uniform(0.6, 1.3), 1.0, 4.0))
        n = int(round(dur * rate_hz))
        e1 = np.cross(phi / max(ang, 1e-9), so3.random_unit(rng))
        e1 /= np.linalg.norm(e1)
        segs.append({'kind': 'turn', 'k': k, 'i0': i, 'i1': i + n, 'qa': qa, 'phi': phi,
                     'skew': rng.uniform(0.8, 1.25),
                     'a1': e1 * min(0.5, rng.uniform(0.10, 0.45) * ang),
                     'a2': so3.random_unit(rng) * rng.uniform(2, 8) * DEG,
                     'f2': rng.uniform(0.7, 2.5), 'p2': rng.uniform(0, 2 * math.pi),
                     'lift_m': rng.uniform(0.02, 0.10),
                     'slide_m': np.append(rng.uniform(-0.15, 0.15, 2), 0.0)})
        i += n
    return segs, i


def draw_tremor(rng, scale):
    terms = []
    for count, (flo, fhi), (alo, ahi) in ((2, (0.1, 0.6), (0.02, 0.15)), (2, (1, 4), (0.005, 0.03)),
                                          (1, (8, 12), (0.002, 0.01))):
        for _ in range(count):
            terms.append((rng.uniform(flo, fhi), scale * rng.uniform(alo, ahi) * DEG,
                          so3.random_unit(rng), rng.uniform(0, 2 * math.pi)))
    return terms


class Motion:
    """The closed-form attitude, body rate and hand acceleration at any times."""

    def __init__(self, segs, tremor, rate_hz):
        self.segs, self.tremor, self.rate = segs, tremor, rate_hz
        self.starts = np.array([s['i0'] for s in segs], float) / rate_hz

    def _tremor(self, t):
        v = np.zeros((len(t), 3))
        vd = np.zeros((len(t), 3))
        for f, amp, axis, ph in self.tremor:
            w = 2 * math.pi * f
            v += np.outer(amp * np.sin(w * t + ph), axis)
            vd += np.outer(amp * w * np.cos(w * t + ph), axis)
        return v, vd

    def _turn(self, s, t):
        d = (s['i1'] - s['i0']) / self.rate
        x = np.clip((t - s['i0'] / self.rate) / d, 0.0, 1.0)
        p = s['skew']
        xs = x**p
        with np.errstate(divide='ignore', invalid='ignore'):
            dxs = np.where(x > 0, p * x**(p - 1), 0.0) / d
        q_nom = so3.mul(s['qa'], so3.exp(np.outer(minjerk(xs), s['phi'])))
        w_nom = np.outer(minjerk_d(xs) * dxs, s['phi'])
        trel = t - s['i0'] / self.rate
        osc = np.sin(2 * math.pi * s['f2'] * trel + s['p2'])
        oscd = 2 * math.pi * s['f2'] * np.cos(2 * math.pi * s['f2'] * trel + s['p2'])
        shape = s['a1'][None, :] + np.outer(osc, s['a2'])
        v = bump(x)[:, None] * shape
        vd = (bump_d(x) / d)[:, None] * shape + np.outer(bump(x) * oscd, s['a2'])
        acc = (np.outer(minjerk_dd(x) / d**2, s['slide_m']) +
               np.outer(bump_dd(x) / d**2 * s['lift_m'], [0.0, 0.0, 1.0]))
        return q_nom, w_nom, v, vd, acc

    def state(self, t):
        """q (n,4) body->world, omega (n,3) rad/s body, hand acceleration (n,3) m/s^2 world."""
        t = np.asarray(t, float)
        n = len(t)
        qa = np.tile([1.0, 0, 0, 0], (n, 1))
        wa = np.zeros((n, 3))
        vb = np.zeros((n, 3))
        vbd = np.zeros((n, 3))
        acc = np.zeros((n, 3))
        seg_of = np.clip(np.searchsorted(self.starts, t, side='right') - 1, 0, len(self.segs) - 1)
        for j in np.unique(seg_of):
            m = seg_of == j
            s = self.segs[j]
            if s['kind'] == 'static':
                qa[m] = s['q']
            else:
                qa[m], wa[m], vb[m], vbd[m], acc[m] = self._turn(s, t[m])
        vc, vcd = self._tremor(t)
        qb, qc = so3.exp(vb), so3.exp(vc)
        wb, wc = so3.right_jacobian_apply(vb, vbd), so3.right_jacobian_apply(vc, vcd)
        q = so3.mul(so3.mul(qa, qb), qc)
        w = so3.rotate_inv(qc, so3.rotate_inv(qb, wa) + wb) + wc
        return q, w, acc


# ---------------------------------------------------------------- simulation
def simulate(args):
    rng = np.random.default_rng(args.seed)
    rate = args.rate
    n_pos = args.positions if args.positions else int(rng.integers(26, 41))
    gravity = G_STD if rng.random() < 0.5 else float(rng.uniform(9.78, 9.832))
    acc_p, gyro_p = draw_sensor(rng, rate)
    latitude = args.latitude if args.latitude is not None else float(rng.uniform(-60, 60))
    omega_e = (EARTH_RATE_RADPS * np.array([0.0, math.cos(latitude * DEG), math.sin(latitude * DEG)])
               if args.earth_rate == 'on' else np.zeros(3))
    lever = so3.random_unit(rng) * args.lever_arm
    positions = place_positions(rng, n_pos)
    segs, n_samples = build_timeline(rng, positions, rate)
    motion = Motion(segs, draw_tremor(rng, args.tremor), rate)

    t = np.arange(n_samples + 1) / rate
    q, w, hand_acc = motion.state(t)
    h = 1e-5  # angular acceleration by a central difference of the closed-form rate
    wdot = (motion.state(t + h)[1] - motion.state(t - h)[1]) / (2 * h)
    f_body = (so3.rotate_inv(q, hand_acc + np.array([0.0, 0.0, gravity])) +
              np.cross(wdot, lever) + np.cross(w, np.cross(w, lever)))
    w_ib = w + so3.rotate_inv(q, np.tile(omega_e, (len(t), 1)))

    tm = t_matrix(acc_p['theta']['yz'], acc_p['theta']['zx'], acc_p['theta']['zy'])
    y_clean = np.array(acc_p['bias_mps2']) + (np.linalg.solve(tm, f_body.T).T * (1 + np.array(acc_p['sfe'])))
    y_acc = y_clean + rng.standard_normal(y_clean.shape) * acc_p['sigma_per_sample_mps2']
    steps = rng.standard_normal((len(t), 3)) * gyro_p['random_walk_radps2_per_sqrt_hz'] * math.sqrt(1 / rate)
    steps[0] = 0
    bias = gyro_p['bias0_radps'] + np.cumsum(steps, axis=0)
    minv = np.linalg.inv(gyro_p['M'])
    g_clean = w_ib @ minv.T + bias
    y_gyro = g_clean + rng.standard_normal(g_clean.shape) * gyro_p['sigma_per_sample_radps']
    sim = dict(rate=rate, gravity=gravity, acc=acc_p, gyro=gyro_p, omega_e=omega_e, latitude=latitude,
               lever=lever, positions=positions, segs=segs, motion=motion, t=t, q=q, w=w,
               f_body=f_body, w_ib=w_ib, bias=bias, y_acc=y_acc, y_gyro=y_gyro, g_clean=g_clean)
    return sim


# ---------------------------------------------------------------- output
def encode(sim, accel_units, gyro_units):
    """Columns as written, the factors that turn them back into SI, and clipped counts."""
    a, g = sim['y_acc'], sim['y_gyro']
    clipped = 0
    if accel_units == 'mps2':
        acols, afac, afmt = a, 1.0, '%.6f'
    elif accel_units == 'g':
        acols, afac, afmt = a / G_STD, G_STD, '%.7f'
    else:
        c = np.round(a * ACCEL_COUNTS_PER_G / G_STD)
        clipped += int(np.sum((c < -32768) | (c > 32767)))
        acols, afac, afmt = np.clip(c, -32768, 32767), G_STD / ACCEL_COUNTS_PER_G, '%d'
    if gyro_units == 'rads':
        gcols, gfac, gfmt = g, 1.0, '%.7f'
    elif gyro_units == 'dps':
        gcols, gfac, gfmt = g / DEG, DEG, '%.5f'
    else:
        c = np.round(g / DEG * GYRO_COUNTS_PER_DPS)
        clipped += int(np.sum((c < -32768) | (c > 32767)))
        gcols, gfac, gfmt = np.clip(c, -32768, 32767), DEG / GYRO_COUNTS_PER_DPS, '%d'
    return acols, afac, afmt, gcols, gfac, gfmt, clipped


def write_csv(path, t, acols, afmt, gcols, gfmt):
    row = ','.join(['%.6f'] + [afmt] * 3 + [gfmt] * 3)
    data = np.column_stack([t, acols, gcols])
    tmp = path + '.part'
    with open(tmp, 'w') as f:
        f.write('t,ax,ay,az,gx,gy,gz\n')
        for start in range(0, len(data), 20000):
            f.write('\n'.join(row % tuple(r) for r in data[start:start + 20000]) + '\n')
    os.replace(tmp, path)


def static_truth(sim, s):
    i0, i1 = s['i0'], s['i1']
    sl = slice(i0, i1 + 1)
    up = so3.rotate_inv(sim['q'][sl], np.tile([0.0, 0.0, 1.0], (i1 - i0 + 1, 1))).mean(axis=0)
    pos = sim['positions'][s['k']]
    return {'index': s['k'], 'start_s': i0 / sim['rate'], 'end_s': i1 / sim['rate'],
            'mid_s': (i0 + i1) / 2 / sim['rate'], 'samples': i1 - i0 + 1,
            'target_up_body': pos['target'], 'target_kind': pos['kind'],
            'q_world_body_start': list(sim['q'][i0]), 'q_world_body_end': list(sim['q'][i1]),
            'up_body_mean': list(up / np.linalg.norm(up)),
            'specific_force_mean_body_mps2': list(sim['f_body'][sl].mean(axis=0)),
            'gyro_bias_start_radps': list(sim['bias'][i0]), 'gyro_bias_end_radps': list(sim['bias'][i1]),
            'gyro_bias_mean_radps': list(sim['bias'][sl].mean(axis=0)),
            'gyro_raw_mean_noise_free_radps': list(sim['g_clean'][sl].mean(axis=0))}


def turn_truth(sim, s):
    i0, i1 = s['i0'], s['i1']
    rel = so3.log(so3.mul(so3.conj(sim['q'][i0]), sim['q'][i1]))
    ang = float(np.linalg.norm(rel))
    rates = np.linalg.norm(sim['w'][i0:i1 + 1], axis=1)
    return {'index': s['k'], 'from_position': s['k'], 'to_position': s['k'] + 1,
            'start_s': i0 / sim['rate'], 'end_s': i1 / sim['rate'],
            'angle_rad': ang, 'axis_body': list(rel / max(ang, 1e-12)),
            'nominal_angle_rad': float(np.linalg.norm(s['phi'])),
            'path_angle_rad': float(np.trapz(rates, dx=1 / sim['rate'])),
            'peak_rate_radps': float(rates.max())}


def truth_json(sim, args, afac, gfac, clipped):
    acc = dict(sim['acc'])
    acc['theta'] = {k: float(v) for k, v in acc['theta'].items()}
    acc['bias_mps2'] = [float(v) for v in acc['bias_mps2']]
    acc['sfe'] = [float(v) for v in acc['sfe']]
    gp = sim['gyro']
    opts = ['--units', args.accel_units]
    if args.gyro_units == 'dps':
        opts += ['--gyro-units', 'dps']
    if args.accel_units == 'counts' or abs(sim['gravity'] - G_STD) > 1e-12:
        opts += ['--gravity', '%.6f' % sim['gravity']]
    return {
        'format': FORMAT, 'generator': 'bench/independent/gen_imu_session.py', 'seed': args.seed,
        'rate_hz': sim['rate'], 'samples': len(sim['t']), 'duration_s': float(sim['t'][-1]),
        'gravity_mps2': sim['gravity'],
        'conventions': {
            'world': 'local level, x east, y north, z up',
            'body': "accelerometer's orthogonalised frame (x along accel x, y in the accel x-y plane)",
            'quaternion': 'Hamilton [w,x,y,z], body to world: v_W = q v_B q*',
            'body_rate': 'dR_world_body/dt = R_world_body [omega]x, omega relative to the world frame',
            'gyro_model': 'raw = M^-1 (omega + R^T earth_rate_world) + bias(t) + noise',
            'accel_model': 'Y = bias + diag(1+sfe) T^-1 f_body + noise (docs/method.md §2)',
            'noise': 'per-sample sigma = density * sqrt(rate_hz)'},
        'accelerometer': acc,
        'gyroscope': {'M': [float(v) for v in gp['M'].ravel()],
                      'M_inverse': [float(v) for v in np.linalg.inv(gp['M']).ravel()],
                      'bias_at_start_radps': [float(v) for v in gp['bias0_radps']],
                      'random_walk_radps2_per_sqrt_hz': gp['random_walk_radps2_per_sqrt_hz'],
                      'noise_density_radps_per_sqrt_hz': gp['noise_density_radps_per_sqrt_hz'],
                      'sigma_per_sample_radps': gp['sigma_per_sample_radps'],
                      'earth_rate_world_radps': [float(v) for v in sim['omega_e']],
                      'latitude_deg': sim['latitude']},
        'lever_arm_body_m': [float(v) for v in sim['lever']],
        'log': {'file': 'session.csv', 'columns': 't,ax,ay,az,gx,gy,gz',
                'accel_units': args.accel_units, 'gyro_units': args.gyro_units,
                'accel_si_per_unit': afac, 'gyro_si_per_unit': gfac, 'clipped_values': clipped,
                'mpcal_options': opts},
        'static_intervals': [static_truth(sim, s) for s in sim['segs'] if s['kind'] == 'static'],
        'turns': [turn_truth(sim, s) for s in sim['segs'] if s['kind'] == 'turn'],
    }


def to_plain(x):
    if isinstance(x, dict):
        return {k: to_plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [to_plain(v) for v in x]
    if isinstance(x, np.generic):
        return x.item()
    return x


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--out', required=True, help='output directory (created)')
    ap.add_argument('--seed', type=int, required=True, help='random seed; same seed, same files')
    ap.add_argument('--positions', type=int, help='static positions, initial rest included (default 26-40)')
    ap.add_argument('--rate', type=float, default=200.0, help='sample rate in Hz (default 200)')
    ap.add_argument('--accel-units', choices=['mps2', 'g', 'counts'], default='mps2',
                    help='accelerometer columns: m/s^2, g or int16 counts at 8192 per g (default mps2)')
    ap.add_argument('--gyro-units', choices=['rads', 'dps', 'counts'], default='rads',
                    help='gyroscope columns: rad/s, deg/s or int16 counts at 16.4 per deg/s (default rads)')
    ap.add_argument('--earth-rate', choices=['on', 'off'], default='on',
                    help='add the Earth rate to the gyroscope (default on)')
    ap.add_argument('--latitude', type=float, help='latitude in deg for the Earth rate (default: drawn)')
    ap.add_argument('--lever-arm', type=float, default=0.05,
                    help='distance in m of the sensor from the centre of rotation (default 0.05; 0 = none)')
    ap.add_argument('--tremor', type=float, default=1.0, help='hand tremor scale (0 = none; default 1)')
    ap.add_argument('--check', action='store_true', help='verify the written session against the truth')
    a = ap.parse_args(argv)
    if a.positions is not None and not 2 <= a.positions <= 200:
        ap.error('--positions must be 2-200')
    if not 20 <= a.rate <= 5000:
        ap.error('--rate must be 20-5000 Hz')
    if a.lever_arm < 0 or a.lever_arm > 0.5:
        ap.error('--lever-arm must be 0-0.5 m')
    if a.tremor < 0 or a.tremor > 10:
        ap.error('--tremor must be 0-10')
    return a


def generate(args):
    """Writes session.csv and truth.json; returns (the simulation, the truth)."""
    os.makedirs(args.out, exist_ok=True)
    sim = simulate(args)
    acols, afac, afmt, gcols, gfac, gfmt, clipped = encode(sim, args.accel_units, args.gyro_units)
    write_csv(os.path.join(args.out, 'session.csv'), sim['t'], acols, afmt, gcols, gfmt)
    truth = to_plain(truth_json(sim, args, afac, gfac, clipped))
    with open(os.path.join(args.out, 'truth.json'), 'w') as f:
        json.dump(truth, f, indent=1)
    return sim, truth


def main(argv=None):
    args = parse_args(argv)
    try:
        sim, truth = generate(args)
    except OSError as e:
        sys.exit('%s: error: cannot write %s: %s; give a writable --out directory'
                 % (os.path.basename(sys.argv[0]), args.out, e.strerror or e))
    print(json.dumps({'file': os.path.join(args.out, 'session.csv'), 'rows': len(sim['t']),
                      'positions': len(truth['static_intervals']), 'duration_s': truth['duration_s'],
                      'opts': truth['log']['mpcal_options']}))
    if args.check and not imu_check.run(sim, args.out, truth):
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
