"""The self-check of gen_still.py --check (see its docstring).

Statistics gathered while streaming (Stats) and compared with the truth
(run): white-part variance, random-walk increment variance, the Allan
deviation of the bias-instability part and of the total from block sums,
and the first rows of the written file.
"""
import math
import os

import numpy as np

import noise_terms

READBACK_ROWS = 2000
CHECK_TAUS_S = (1.0, 10.0, 100.0, 1000.0)
MIN_CLUSTERS = 20
SIGMAS = 4.0
SHORT_M = (1, 2, 4)
NAMES = ('ax', 'ay', 'az', 'gx', 'gy', 'gz')


class Stats:
    def __init__(self, channels, block_s):
        self.block_s = block_s
        self.white_ss = np.zeros(channels)
        self.steps_ss = np.zeros(channels)
        self.count = 0
        self.total_blocks, self.bi_blocks = [], []
        self.first_rows = None
        self.short_ss = np.zeros((channels, len(SHORT_M)))
        self.short_count = np.zeros(len(SHORT_M))

    def add(self, cols, parts, nb, first_rows):
        n = cols.shape[1]
        self.white_ss += [float(np.dot(p['white'], p['white'])) for p in parts]
        self.steps_ss += [float(np.dot(p['steps'], p['steps'])) for p in parts]
        self.count += n
        whole = n // nb * nb
        self.total_blocks.append(cols[:, :whole].reshape(len(cols), -1, nb).mean(axis=2))
        bi = np.array([p['bias_instability'][:whole] for p in parts])
        self.bi_blocks.append(bi.reshape(len(cols), -1, nb).mean(axis=2))
        theta = np.cumsum(cols, axis=1)  # in units of tau0: second differences of theta per chunk
        for j, m in enumerate(SHORT_M):
            d = theta[:, 2 * m:] - 2 * theta[:, m:-m] + theta[:, :-2 * m]
            self.short_ss[:, j] += np.einsum('ij,ij->i', d, d)
            self.short_count[j] += d.shape[1]
        if self.first_rows is None:
            self.first_rows = first_rows


def allan_dev_blocks(means, block_s, m):
    """Overlapping Allan deviation at tau = m blocks from block means (docs/method.md §8)."""
    theta = np.concatenate([[0.0], np.cumsum(means)]) * block_s
    d = theta[2 * m:] - 2 * theta[m:-m] + theta[:-2 * m]
    tau = m * block_s
    return math.sqrt(float(np.dot(d, d)) / (2 * tau * tau * len(d)))


def measured_b_ratio(bi, block_s, chans):
    """Per channel, the B read from the generated bias-instability part alone, over the true B."""
    lo, hi = noise_terms.PLATEAU_S
    hi = min(hi, bi.shape[1] * block_s / MIN_CLUSTERS)
    if hi < lo:
        return 'record too short for the plateau'
    ms = np.unique(np.round(np.logspace(math.log10(lo), math.log10(hi), 13) / block_s).astype(int))
    out = []
    for c, (_, _, b, _) in enumerate(chans):
        if b > 0:
            dev = [allan_dev_blocks(bi[c], block_s, m) for m in ms]
            out.append('%s %.3f' % (NAMES[c], float(np.median(dev)) / noise_terms.FLICKER_FACTOR / b))
    return ' '.join(out)


def per_channel(truth):
    """(N, K, B, Q) for the six channels from the truth file."""
    return [c[:4] for c in channels(truth)]


def channels(truth):
    """(N, K, B, Q, extra) for the six channels, extra the keyword arguments of
    noise_terms.allan_var_terms for the low-pass, bump and sinusoid."""
    out = []
    for sensor, u, un, uk, uq in (('accel', 'mps2', 'mps2_per_sqrt_hz', 'mps3_per_sqrt_hz', 'mps'),
                                  ('gyro', 'radps', 'radps_per_sqrt_hz', 'radps2_per_sqrt_hz', 'rad')):
        t = truth[sensor]
        for i in range(3):
            extra = {'lowpass_hz': truth.get('lowpass_hz', 0.0)}
            if 'gauss_markov_bump' in t:
                extra['bump'] = (t['gauss_markov_bump']['sigma_' + u][i], t['gauss_markov_bump']['tau_c_s'])
                extra['sine'] = (t['sine']['amplitude_' + u][i], t['sine']['period_s'])
            out.append((t['noise_density_' + un][i], t['random_walk_' + uk][i],
                        t['bias_instability_' + u][i], t['quantisation_' + uq][i], extra))
    return out


def run(stats, truth, out_dir):
    rate, n = truth['rate_hz'], stats.count
    ok = True

    def verdict(name, passed, text):
        nonlocal ok
        ok &= bool(passed)
        print('check %s: %s  %s' % (name, 'ok' if passed else 'FAILED', text))

    chans = per_channel(truth)
    extras = [c[4] for c in channels(truth)]
    tol = SIGMAS * math.sqrt(2.0 / n)
    white = stats.white_ss / n / np.array([c[0]**2 * rate for c in chans]) - 1
    verdict('white variance / (N^2 R) - 1', np.all(abs(white) < tol),
            ' '.join('%s %+.4f' % kv for kv in zip(NAMES, white)) + ' (bar %.4f)' % tol)
    k = np.array([c[1] for c in chans])
    steps = np.where(k > 0, stats.steps_ss / n / np.maximum(k**2 / rate, 1e-300) - 1, 0.0)
    verdict('random-walk increment variance / (K^2/R) - 1', np.all(abs(steps) < tol),
            ' '.join('%s %+.4f' % kv for kv in zip(NAMES, steps)) + ' (bar %.4f)' % tol)
    worst, lines = 0.0, []
    for j, m in enumerate(SHORT_M):
        bar = SIGMAS / math.sqrt(2 * (n / m - 1))
        for c, (nd, kr, b, q) in enumerate(chans):
            q2 = noise_terms.gm_variance_for(b, 1.0 / rate)[0] if b > 0 else 0.0
            expect = sum(v[0] for v in noise_terms.allan_var_terms([m / rate], 1.0 / rate, nd, kr, q2, q,
                                                                   **extras[c]).values())
            rel = math.sqrt(stats.short_ss[c, j] / (2 * m * m * stats.short_count[j]) / expect) - 1
            worst = max(worst, abs(rel) / bar)
            lines.append('%s@%dtau0 %+.4f' % (NAMES[c], m, rel))
    verdict('Allan deviation of the total at %s sample intervals / exact - 1' % ','.join(map(str, SHORT_M)),
            worst <= 1.0, '%s; worst %.2f of its bar' % (' '.join(lines), worst))
    total = np.concatenate(stats.total_blocks, axis=1)
    bi = np.concatenate(stats.bi_blocks, axis=1)
    tau0 = 1.0 / rate
    for label, series, which in (('bias-instability part', bi, 'bias_instability'), ('total', total, None)):
        worst, lines = 0.0, []
        for tau in CHECK_TAUS_S:
            m = int(round(tau / stats.block_s))
            if m < 1 or series.shape[1] / m < MIN_CLUSTERS:
                continue
            bar = SIGMAS / math.sqrt(2 * (series.shape[1] / m - 1))
            for c, (nd, kr, b, q) in enumerate(chans):
                q2 = noise_terms.gm_variance_for(b, tau0)[0] if b > 0 else 0.0
                parts = noise_terms.allan_var_terms([m * stats.block_s], tau0, nd, kr, q2, q, **extras[c])
                expect = math.sqrt(parts[which][0] if which else sum(v[0] for v in parts.values()))
                if expect == 0:
                    continue
                rel = allan_dev_blocks(series[c], stats.block_s, m) / expect - 1
                worst = max(worst, abs(rel) / bar)
                lines.append('%s@%gs %+.3f' % (NAMES[c], tau, rel))
        verdict('Allan deviation of the %s / exact - 1' % label, worst <= 1.0,
                '%s; worst %.2f of its bar' % (' '.join(lines) if lines else 'no tau with enough clusters', worst))
    print('measured B (median Allan deviation of the bias-instability part over %g-%g s / 0.664) / true B: %s'
          % (noise_terms.PLATEAU_S + (measured_b_ratio(bi, stats.block_s, chans),)))
    path = os.path.join(out_dir, truth['log']['file'])
    back = np.loadtxt(path, delimiter=',', skiprows=1, max_rows=READBACK_ROWS, ndmin=2)
    with open(path, 'rb') as f:
        lines = sum(buf.count(b'\n') for buf in iter(lambda: f.read(1 << 24), b''))
    diff = float(np.max(np.abs(back - stats.first_rows[:len(back)])))
    verdict('still.csv read back', diff < 1e-5 and lines == n + 1,
            '%d lines (%d expected), first %d rows differ by at most %.1e' % (lines, n + 1, len(back), diff))
    return ok
