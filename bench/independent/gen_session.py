#!/usr/bin/env python3
"""Independent multi-position accelerometer session generator (plain Python).

Written from the error model of docs/method.md §2 and the README's
"Conventions" (units, directions, the calibration file's frame), independently
of mpcal's own simulator (src/simulate), so that study.py tests mpcal on
sessions that its own simulator did not make.

A session is: an initial rest, then N static positions held 5-20 s, joined by
hand turns (min-jerk slerp of the attitude + a lift/slide of the device +
0.5-3 Hz and ~9 Hz hand tremor + occasional bumps), then a small placement
wobble when the device is put down.  Readings:

    Y = b + diag(1+s) * inv(T) * f_body      (m/s^2)
    f_body = R^T (a_lin_world + [0,0,G])     (specific force, G = |g|)

plus white noise (optionally a slightly coloured AR(1) part), then written as
g, m/s^2 or integer ADC counts (Y_c = zero + k*Y, k = counts per m/s^2, clipped
to the ADC range) in one of many logger formats.

Usage:
  gen_session.py --seed N --out DIR   -> DIR/session.<ext> and DIR/meta.json
                                         (the truth and the mpcal options the log needs)
The same seed always gives the same files.
"""
import argparse, json, math, os, random

G_STD = 9.80665

# ---------------------------------------------------------------- quaternions
def qmul(a, b):
    aw, ax, ay, az = a; bw, bx, by, bz = b
    return (aw*bw - ax*bx - ay*by - az*bz,
            aw*bx + ax*bw + ay*bz - az*by,
            aw*by - ax*bz + ay*bw + az*bx,
            aw*bz + ax*by - ay*bx + az*bw)

def qconj(q):
    return (q[0], -q[1], -q[2], -q[3])

def qnorm(q):
    n = math.sqrt(sum(c*c for c in q)); return tuple(c/n for c in q)

def qrot(q, v):
    """rotate vector v by q (body->world when q is the attitude)"""
    p = qmul(qmul(q, (0.0, v[0], v[1], v[2])), qconj(q))
    return (p[1], p[2], p[3])

def qaxang(axis, ang):
    n = math.sqrt(sum(c*c for c in axis))
    if n < 1e-15 or abs(ang) < 1e-15:
        return (1.0, 0.0, 0.0, 0.0)
    s = math.sin(ang/2)/n
    return (math.cos(ang/2), axis[0]*s, axis[1]*s, axis[2]*s)

def qrotvec(rv):
    ang = math.sqrt(sum(c*c for c in rv))
    return qaxang(rv, ang) if ang > 0 else (1.0, 0.0, 0.0, 0.0)

def cross(a, b):
    return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])

def dot(a, b):
    return a[0]*b[0]+a[1]*b[1]+a[2]*b[2]

def unit(v):
    n = math.sqrt(dot(v, v)); return (v[0]/n, v[1]/n, v[2]/n)

def q_from_to(u, v):
    u = unit(u); v = unit(v)
    c = max(-1.0, min(1.0, dot(u, v)))
    ax = cross(u, v)
    if math.sqrt(dot(ax, ax)) < 1e-9:
        if c > 0: return (1.0, 0.0, 0.0, 0.0)
        p = cross(u, (1, 0, 0)) if abs(u[0]) < 0.9 else cross(u, (0, 1, 0))
        return qaxang(p, math.pi)
    return qaxang(ax, math.acos(c))

def slerp(a, b, t):
    d = sum(x*y for x, y in zip(a, b))
    if d < 0:
        b = tuple(-x for x in b); d = -d
    if d > 0.9999995:
        return qnorm(tuple(x + t*(y-x) for x, y in zip(a, b)))
    th = math.acos(min(1.0, d)); s = math.sin(th)
    wa = math.sin((1-t)*th)/s; wb = math.sin(t*th)/s
    return tuple(wa*x + wb*y for x, y in zip(a, b))

def qangle(a, b):
    d = abs(sum(x*y for x, y in zip(a, b)))
    return 2*math.acos(min(1.0, d))

def attitude_for_up(u, yaw):
    """attitude q (body->world) whose body-frame 'up' (specific force direction) is u"""
    q = q_from_to(u, (0.0, 0.0, 1.0))      # maps u to world z
    return qnorm(qmul(qaxang((0, 0, 1), yaw), q))

def rand_unit(rng):
    while True:
        v = (rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))
        n = math.sqrt(dot(v, v))
        if n > 1e-6: return (v[0]/n, v[1]/n, v[2]/n)

def tilt(rng, u, max_deg):
    """u tilted by up to max_deg in a random direction"""
    p = unit(cross(u, rand_unit(rng)))
    return qrot(qaxang(p, math.radians(rng.uniform(0, max_deg))), u)

def cube_dirs():
    out = []
    for x in (-1, 0, 1):
        for y in (-1, 0, 1):
            for z in (-1, 0, 1):
                if (x, y, z) != (0, 0, 0):
                    out.append(unit((x, y, z)))
    return out

# ---------------------------------------------------------------- error model
def Tmat(tyz, tzx, tzy):
    return [[1.0, 0.0, 0.0],
            [math.tan(tyz), 1/math.cos(tyz), 0.0],
            [math.tan(tzx)*math.tan(tyz) - math.tan(tzy)/math.cos(tzx),
             math.tan(tzx)/math.cos(tyz), 1/(math.cos(tzx)*math.cos(tzy))]]

def lower_inv(L):
    """inverse of a 3x3 lower-triangular matrix by forward substitution"""
    inv = [[0.0]*3 for _ in range(3)]
    for c in range(3):
        e = [1.0 if i == c else 0.0 for i in range(3)]
        x = [0.0]*3
        for i in range(3):
            x[i] = (e[i] - sum(L[i][j]*x[j] for j in range(i))) / L[i][i]
        for i in range(3): inv[i][c] = x[i]
    return inv

def matvec(M, v):
    return tuple(M[i][0]*v[0] + M[i][1]*v[1] + M[i][2]*v[2] for i in range(3))

# ---------------------------------------------------------------- motion
def minjerk(t):   # position profile 0..1 and its 2nd derivative
    return 10*t**3 - 15*t**4 + 6*t**5, 60*t - 180*t**2 + 120*t**3

def bump_profile(t):   # 64 t^3 (1-t)^3 (peak 1 at 0.5) and 2nd derivative
    return 64*t**3*(1-t)**3, 64*6*t*(1-t)*(1 - 5*t + 5*t*t)

class Turn:
    def __init__(self, rng, qa, qb, t0, dur):
        self.qa, self.qb, self.t0, self.d = qa, qb, t0, dur
        hz = rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)
        self.D = (hz[0], hz[1], 0.0)                       # slide (m)
        self.h = rng.uniform(0.02, 0.15)                   # lift (m)
        # angular tremor: 2 components 0.5-3 Hz + one physiological ~8-11 Hz
        self.atrem = []
        for f, amp in ((rng.uniform(0.5, 3), rng.uniform(0.3, 1.5)), (rng.uniform(0.5, 3), rng.uniform(0.2, 1.0)),
                       (rng.uniform(8, 11), rng.uniform(0.05, 0.2))):
            self.atrem.append((f, math.radians(amp), rand_unit(rng), rng.uniform(0, 2*math.pi)))
        # linear tremor a few mg
        self.ltrem = [(rng.uniform(0.5, 3), rng.uniform(2, 8)*1e-3*G_STD, rand_unit(rng), rng.uniform(0, 2*math.pi))
                      for _ in range(2)]
        self.bumps = []
        if rng.random() < 0.2:
            self.bumps.append((t0 + dur*rng.uniform(0.2, 0.8), rng.uniform(0.015, 0.04),
                               rng.uniform(0.05, 0.35)*G_STD, rand_unit(rng)))

    def state(self, t):
        tau = (t - self.t0)/self.d
        s, _ = minjerk(tau)
        env = math.sin(math.pi*tau)**2
        q = slerp(self.qa, self.qb, s)
        rv = [0.0, 0.0, 0.0]
        for f, amp, ax, ph in self.atrem:
            a = amp*env*math.sin(2*math.pi*f*(t - self.t0) + ph)
            for i in range(3): rv[i] += a*ax[i]
        q = qnorm(qmul(q, qrotvec(rv)))
        _, s2 = minjerk(tau); _, b2 = bump_profile(tau)
        a = [self.D[i]*s2/self.d**2 for i in range(3)]
        a[2] += self.h*b2/self.d**2
        for f, amp, ax, ph in self.ltrem:
            v = amp*env*math.sin(2*math.pi*f*(t - self.t0) + ph)
            for i in range(3): a[i] += v*ax[i]
        for tb, db, ab, ax in self.bumps:
            if tb <= t < tb + db:
                v = ab*math.sin(math.pi*(t - tb)/db)
                for i in range(3): a[i] += v*ax[i]
        return q, a

class Wobble:   # placement: damped oscillation after the device is put down
    def __init__(self, rng, t0):
        self.t0 = t0
        self.f = rng.uniform(6, 15); self.A = rng.uniform(1, 5)*1e-3*G_STD
        self.tau = rng.uniform(0.03, 0.08); self.ax = rand_unit(rng)

    def acc(self, t):
        dt = t - self.t0
        if dt < 0 or dt > 12*self.tau: return None
        v = self.A*math.exp(-dt/self.tau)*math.sin(2*math.pi*self.f*dt)
        return [v*c for c in self.ax]

# ---------------------------------------------------------------- formats
# name: (separator, header or None, column layout, --columns mapping or None)
# layout tokens: t, ax, ay, az, gx, gy, gz, temp, seq, mx, my, mz, batt
FORMATS = {
    'csv_hdr_time_acc':   (',',  'time,acc_x,acc_y,acc_z', ['t', 'ax', 'ay', 'az'], None),
    'semi_hdr_ts':        (';',  'timestamp;ax;ay;az', ['t', 'ax', 'ay', 'az'], None),
    'space_hdr_gyro_temp': (' ', 't ax ay az gx gy gz temp', ['t', 'ax', 'ay', 'az', 'gx', 'gy', 'gz', 'temp'], None),
    'tab_hdr_extra':      ('\t', 'seq\ttimestamp\taccel_x\taccel_y\taccel_z\tmag_x\tmag_y\tmag_z',
                           ['seq', 't', 'ax', 'ay', 'az', 'mx', 'my', 'mz'], None),
    'csv_hdr_accX_gyro':  (',',  'timestamp,accX,accY,accZ,gyro_x,gyro_y,gyro_z', ['t', 'ax', 'ay', 'az', 'gx', 'gy', 'gz'], None),
    'csv_hdr_caps_names': (',',  'Time,AX,AY,AZ,Temp', ['t', 'ax', 'ay', 'az', 'temp'], None),
    'csv_noheader':       (',',  None, ['t', 'ax', 'ay', 'az'], None),
    'space_noheader_aligned': ('  ', None, ['t', 'ax', 'ay', 'az'], None),
    'tab_noheader':       ('\t', None, ['t', 'ax', 'ay', 'az'], None),
    'csv_noheader_extra': (',',  None, ['seq', 't', 'ax', 'ay', 'az', 'temp'], 't=1,ax=2,ay=3,az=4'),
    'semi_noheader_reordered': (';', None, ['ax', 'ay', 'az', 't'], 't=3,ax=0,ay=1,az=2'),
    'space_noheader_zyx': (' ',  None, ['t', 'az', 'ay', 'ax', 'temp'], 't=0,ax=3,ay=2,az=1'),
    'csv_hdr_named_map':  (',',  'ts_ms,accel_x_mg,accel_y_mg,accel_z_mg,batt', ['t', 'ax', 'ay', 'az', 'batt'],
                           't=ts_ms,ax=accel_x_mg,ay=accel_y_mg,az=accel_z_mg'),
    'csv_hdr_index_rate': (',',  'index,ax,ay,az', ['seq', 'ax', 'ay', 'az'], None),
}

TIME_STYLES = ['s', 's_epoch', 'ms', 'ms_epoch', 'us', 'us_epoch', 'ns', 'ns_epoch']

COUNT_CONFIGS = [  # name, zero, counts per g, lo, hi
    ('u16_32768_16384', 32768, 16384, 0, 65535),
    ('u16_32768_4096', 32768, 4096, 0, 65535),
    ('u12_2048_256', 2048, 256, 0, 4095),
    ('s16_0_16384', 0, 16384, -32768, 32767),
    ('s16_0_4096', 0, 4096, -32768, 32767),
    ('s16_0_1000', 0, 1000, -32768, 32767),
]

# ---------------------------------------------------------------- session
def draw_config(seed):
    rng = random.Random(seed)
    c = {'seed': seed}
    c['rate'] = rng.choice([50, 52, 64, 100, 100, 104, 125, 128, 200, 200, 160, rng.uniform(50, 200)])
    c['n_pos'] = rng.randint(14, 30)
    c['layout'] = rng.choice(['cube', 'random', 'cube+random'])
    c['dwell'] = rng.uniform(5, 20)
    c['rest'] = rng.uniform(10, 40)
    c['units'] = rng.choice(['g', 'mps2', 'counts'])
    c['format'] = rng.choice(sorted(FORMATS))
    if c['format'] == 'csv_hdr_index_rate':
        c['time_style'] = 'index'
    elif c['format'] == 'csv_hdr_named_map':
        c['time_style'] = rng.choice(['ms', 'ms_epoch'])
    else:
        c['time_style'] = rng.choice(TIME_STYLES)
    c['comments'] = rng.random() < 0.4
    c['crlf'] = rng.random() < 0.3
    c['gravity'] = G_STD if rng.random() < 0.5 else rng.uniform(9.78, 9.832)
    c['bias_mps2'] = [rng.uniform(-0.3, 0.3)*G_STD for _ in range(3)]
    c['sfe'] = [rng.uniform(-0.06, 0.06) for _ in range(3)]
    c['theta'] = {'yz': rng.uniform(-0.02, 0.02), 'zx': rng.uniform(-0.02, 0.02), 'zy': rng.uniform(-0.02, 0.02)}
    c['noise_density'] = rng.uniform(0.0008, 0.004)          # m/s^2/sqrt(Hz)
    c['colored'] = rng.random() < 0.25
    c['ar_rel'] = rng.uniform(0.1, 0.3) if c['colored'] else 0.0   # std of AR(1) part / white std
    c['ar_tau'] = rng.uniform(0.01, 0.05)
    if c['units'] == 'counts':
        cc = rng.choice(COUNT_CONFIGS)
        c['counts'] = {'name': cc[0], 'zero': cc[1], 'cpg': cc[2], 'lo': cc[3], 'hi': cc[4]}
        # the ADC must dither: white sigma >= ~0.8 LSB
        lsb = G_STD/cc[2]
        sig = c['noise_density']*math.sqrt(c['rate']/2)
        if sig < 0.8*lsb:
            c['noise_density'] = rng.uniform(0.8, 1.5)*lsb/math.sqrt(c['rate']/2)
    c['decimals'] = rng.choice([4, 5, 6]) if c['units'] == 'mps2' else rng.choice([5, 6])
    c['end_motion'] = rng.random() < 0.5
    return c, rng

def orientation_list(c, rng):
    n = c['n_pos']; lay = c['layout']
    cube = cube_dirs(); rng.shuffle(cube)
    if lay == 'cube':
        base = cube[:n] + [rand_unit(rng) for _ in range(max(0, n - 26))]
        ups = [tilt(rng, u, 6) for u in base]
    elif lay == 'random':
        ups = [rand_unit(rng) for _ in range(n)]
    else:
        k = rng.randint(n//2, n)
        ups = [tilt(rng, u, 6) for u in cube[:min(k, 26)]]
        ups += [rand_unit(rng) for _ in range(n - len(ups))]
    rng.shuffle(ups)
    return ups

def build_timeline(c, rng):
    """list of segments: ('static', t0, t1, q) / ('turn', Turn) and wobbles"""
    ups = orientation_list(c, rng)
    rest_up = tilt(rng, (0, 0, 1), 4)
    atts = [attitude_for_up(rest_up, rng.uniform(0, 2*math.pi))]
    for u in ups:
        atts.append(attitude_for_up(u, rng.uniform(0, 2*math.pi)))
    # consecutive positions at least 20 deg apart (in up direction): reorder greedily if not
    def upangle(i, j):
        return math.degrees(math.acos(max(-1, min(1, dot(qrot(qconj(atts[i]), (0, 0, 1)), qrot(qconj(atts[j]), (0, 0, 1)))))))
    for i in range(1, len(atts)):
        if upangle(i-1, i) < 20:
            for j in range(i+1, len(atts)):
                atts[i], atts[j] = atts[j], atts[i]
                if upangle(i-1, i) >= 20:
                    break
    segs = []; wobbles = []
    t = 0.0
    segs.append(('static', t, t + c['rest'], atts[0])); t += c['rest']
    truth_pos = [(0.0, c['rest'])]
    for i in range(1, len(atts)):
        ang = math.degrees(qangle(atts[i-1], atts[i]))
        dur = min(4.0, max(1.5, 1.2 + ang/90*rng.uniform(0.8, 1.4)))
        segs.append(('turn', Turn(rng, atts[i-1], atts[i], t, dur)))
        t += dur
        wobbles.append(Wobble(rng, t))
        dw = c['dwell']*rng.uniform(0.8, 1.2)
        segs.append(('static', t, t + dw, atts[i]))
        truth_pos.append((t, t + dw))
        t += dw
    if c['end_motion']:
        qe = qmul(atts[-1], qaxang(rand_unit(rng), math.radians(rng.uniform(30, 90))))
        segs.append(('turn', Turn(rng, atts[-1], qnorm(qe), t, 1.5)))
        t += 1.5
    return segs, wobbles, truth_pos, t

def simulate(c, rng):
    segs, wobbles, truth_pos, T_end = build_timeline(c, rng)
    rate = c['rate']; dt = 1.0/rate
    n = int(T_end*rate)
    G = c['gravity']
    Tinv = lower_inv(Tmat(c['theta']['yz'], c['theta']['zx'], c['theta']['zy']))
    b = c['bias_mps2']; s = c['sfe']
    sig_w = c['noise_density']*math.sqrt(rate/2)
    phi = math.exp(-dt/c['ar_tau'])
    sig_ar = c['ar_rel']*sig_w
    ar_drive = sig_ar*math.sqrt(1 - phi*phi)
    ar = [rng.gauss(0, sig_ar) for _ in range(3)]
    gyro_b = [rng.uniform(-0.02, 0.02) for _ in range(3)]
    seg_i = 0
    Ys = []; qs = []
    wi = 0
    for idx in range(n + 1):
        t = idx*dt
        while seg_i < len(segs) - 1:
            sg = segs[seg_i]
            end = sg[2] if sg[0] == 'static' else sg[1].t0 + sg[1].d
            if t >= end: seg_i += 1
            else: break
        sg = segs[seg_i]
        if sg[0] == 'static':
            q = sg[3]; a = [0.0, 0.0, 0.0]
        else:
            tt = min(t, sg[1].t0 + sg[1].d)
            q, a = sg[1].state(tt)
        while wi < len(wobbles) - 1 and t > wobbles[wi].t0 + 12*wobbles[wi].tau:
            wi += 1
        if wobbles:
            w = wobbles[wi].acc(t)
            if w is not None:
                a = [a[i] + w[i] for i in range(3)]
        fw = (a[0], a[1], a[2] + G)
        fb = qrot(qconj(q), fw)
        m = matvec(Tinv, fb)
        Y = []
        for i in range(3):
            ar[i] = phi*ar[i] + rng.gauss(0, ar_drive) if sig_ar > 0 else 0.0
            Y.append(b[i] + (1 + s[i])*m[i] + rng.gauss(0, sig_w) + ar[i])
        Ys.append(Y); qs.append(q)
    # gyro (rad/s, body frame) from the attitude sequence
    gyro = []
    for i in range(len(qs)):
        j = min(i + 1, len(qs) - 1); k = j - 1 if j == i else i
        dq = qmul(qconj(qs[k]), qs[j])
        if dq[0] < 0: dq = tuple(-x for x in dq)
        w = [2*dq[1]/dt + gyro_b[0] + rng.gauss(0, 0.004), 2*dq[2]/dt + gyro_b[1] + rng.gauss(0, 0.004),
             2*dq[3]/dt + gyro_b[2] + rng.gauss(0, 0.004)]
        gyro.append(w)
    return Ys, gyro, truth_pos, T_end

def fmt_time(c, idx, t0_epoch):
    rate = c['rate']; st = c['time_style']; t = idx/rate
    if st == 's': return '%.6f' % t
    if st == 's_epoch': return '%.6f' % (t0_epoch + t)
    if st == 'ms': return '%d' % round(t*1e3)
    if st == 'ms_epoch': return '%d' % round(t0_epoch*1e3 + t*1e3)
    if st == 'us': return '%d' % round(t*1e6)
    if st == 'us_epoch': return '%d' % (round(t0_epoch*1e6) + round(t*1e6))
    if st == 'ns': return '%d' % round(t*1e9)
    if st == 'ns_epoch': return '%d' % (round(t0_epoch*1e9) + round(t*1e9))
    if st == 'index': return '%d' % idx
    raise ValueError(st)

def write_session(c, rng, Ys, gyro, path):
    sep, header, layout, cols = FORMATS[c['format']]
    units = c['units']
    t0_epoch = 1.73e9 + rng.uniform(0, 3e7) + 0.123456 if 'epoch' in c['time_style'] else 0.0
    if units == 'counts':
        cc = c['counts']; k = cc['cpg']/G_STD
    eol = '\r\n' if c['crlf'] else '\n'
    lines = []
    if c['comments']:
        lines.append('# logger fw 2.3.1, device IMU-%04d, seed %d' % (rng.randint(0, 9999), c['seed']))
        lines.append('# started %s' % ('2024-11-05T10:22:31Z'))
    if header is not None:
        lines.append(header)
    temp = 24.0 + rng.uniform(-3, 3)
    mid_comment_at = rng.randint(len(Ys)//4, 3*len(Ys)//4) if c['comments'] else -1
    for idx, Y in enumerate(Ys):
        if idx == mid_comment_at:
            lines.append('# marker: battery ok')
        vals = {}
        if units == 'counts':
            for i, nm in enumerate(('ax', 'ay', 'az')):
                v = int(round(cc['zero'] + k*Y[i]))
                vals[nm] = '%d' % max(cc['lo'], min(cc['hi'], v))
        elif units == 'g':
            for i, nm in enumerate(('ax', 'ay', 'az')):
                vals[nm] = '%.*f' % (c['decimals'], Y[i]/G_STD)
        else:
            for i, nm in enumerate(('ax', 'ay', 'az')):
                vals[nm] = '%.*f' % (c['decimals'], Y[i])
        vals['t'] = fmt_time(c, idx, t0_epoch)
        vals['seq'] = '%d' % idx
        g = gyro[idx]
        vals['gx'], vals['gy'], vals['gz'] = ('%.5f' % g[0], '%.5f' % g[1], '%.5f' % g[2])
        vals['temp'] = '%.2f' % (temp + 0.001*idx/c['rate'] + rng.gauss(0, 0.02))
        vals['mx'], vals['my'], vals['mz'] = ('%.2f' % (20 + rng.gauss(0, 0.3)), '%.2f' % (-5 + rng.gauss(0, 0.3)), '%.2f' % (40 + rng.gauss(0, 0.3)))
        vals['batt'] = '%.3f' % (3.9 - 1e-5*idx)
        if c['format'] == 'space_noheader_aligned':
            lines.append('  '.join('%14s' % vals[x] for x in layout))
        else:
            lines.append(sep.join(vals[x] for x in layout))
    text = eol.join(lines) + eol
    with open(path, 'w', newline='', encoding='utf-8') as f:
        f.write(text)

def cli_opts(c):
    o = ['--units', c['units']]
    if c['units'] == 'counts' or abs(c['gravity'] - G_STD) > 1e-9:
        o += ['--gravity', '%.5f' % c['gravity']]
    cols = FORMATS[c['format']][3]
    if cols: o += ['--columns', cols]
    if c['time_style'] == 'index':
        o += ['--rate', repr(c['rate'])]
    return o

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, required=True)
    ap.add_argument('--out', required=True)
    a = ap.parse_args()
    c, rng = draw_config(a.seed)
    os.makedirs(a.out, exist_ok=True)
    Ys, gyro, truth_pos, T_end = simulate(c, rng)
    ext = {',': 'csv', ';': 'csv', '\t': 'tsv', ' ': 'txt', '  ': 'txt'}[FORMATS[c['format']][0]]
    path = os.path.join(a.out, 'session.' + ext)
    write_session(c, rng, Ys, gyro, path)
    sig_w = c['noise_density']*math.sqrt(c['rate']/2)
    phi = math.exp(-1.0/c['rate']/c['ar_tau'])
    infl = math.sqrt((1 + c['ar_rel']**2*(1 + phi)/(1 - phi))/(1 + c['ar_rel']**2))
    meta = dict(config=c, file=path, opts=cli_opts(c), rows=len(Ys), duration_s=T_end,
                positions_generated=len(truth_pos), static_intervals=truth_pos,
                sigma_white_per_sample_mps2=sig_w,
                mean_noise_inflation_vs_sample_std=infl)
    with open(os.path.join(a.out, 'meta.json'), 'w') as f:
        json.dump(meta, f, indent=1)
    print(json.dumps({'file': path, 'opts': cli_opts(c), 'rows': len(Ys)}))

if __name__ == '__main__':
    main()
