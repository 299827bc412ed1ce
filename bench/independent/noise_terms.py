"""Continuous-time noise terms of one sensor axis, their streaming generation
and their exact Allan variance (for gen_still.py).

Terms (IEEE Std 952 / 1293 coefficients, SI):
  N  white noise density: per-sample sigma N sqrt(rate); Allan N^2 / tau.
  K  rate random walk: increments K sqrt(1/rate) per sample; Allan
     K^2 tau / 3 + K^2 tau0^2 / (6 tau) (the second term: discrete sampling).
  B  bias instability: a sum of first-order Gauss-Markov processes with
     correlation times TAU_C_S (two per decade, 0.01-100000 s) and equal
     stationary variance q^2; equal variances at geometric correlation times
     give a 1/f spectrum between them, i.e. a flat Allan deviation.  q is set
     so that the median Allan deviation of the sum over log-spaced tau in
     PLATEAU_S (0.1-10000 s) is 0.664 B; the ripple over that range is about
     +-1.3 % (computed exactly and written to the truth).
     The flicker range must cover every cluster time an analysis fits (one
     sample interval to a quarter of the record, 7200 s at 8 h): IEEE 952's
     B is a 1/f rate noise whose Allan deviation is flat at every tau, and a
     Gauss-Markov sum is flat only between its shortest and longest
     correlation times.  The first set (0.5-5000 s) fell to 0.84 of the
     plateau at 1 s and 0.39 at 0.1 s: where the white noise and B meet
     (1-10 s), points with thousands of degrees of freedom, the curve was
     not the IEEE model, and a fit of that model bent B and K to match them,
     K 1.1-1.4x the truth on the exact expected curve.
  Q  quantisation (optional): the integrated signal theta is rounded to a
     step sqrt(12) Q and the sample is the difference of rounded thetas over
     tau0; Allan 3 Q^2 / tau^2.
The Allan variances are exact for the discrete processes generated here
(Gauss-Markov: through the variance of sums of an AR(1) sequence).
"""
import math

import numpy as np

TAU_C_S = tuple(0.01 * 10 ** (k / 2) for k in range(15))    # 0.01 .. 100000 s
PLATEAU_S = (0.1, 10000.0)
CONVOLVE_MAX = 200                                           # taps of the short-memory filter
FLICKER_FACTOR = 0.664                                       # sqrt(2 ln 2 / pi)
SAFE_EXPONENT = 20.0                                         # phi^-n <= e^20 in a block


def gm_sum_var(n, phi, q2):
    """Var(sum of n consecutive samples) of a stationary AR(1) with variance q2."""
    n = np.asarray(n, float)
    one_m_phi = -math.expm1(math.log(phi)) if phi > 0 else 1.0
    one_m_phin = -np.expm1(n * math.log(phi)) if phi > 0 else np.ones_like(n)
    return q2 * (n * (1 + phi) / one_m_phi - 2 * phi * one_m_phin / one_m_phi**2)


def allan_var_gm(m, tau0, tau_c, q2):
    phi = math.exp(-tau0 / tau_c)
    m = np.asarray(m, float)
    return (4 * gm_sum_var(m, phi, q2) - gm_sum_var(2 * m, phi, q2)) / (2 * m * m)


def allan_var_terms(tau, tau0, n_density, k_rw, gm_q2, q_coeff):
    """Dict of the Allan variance of each term at cluster times tau (multiples of tau0)."""
    tau = np.asarray(tau, float)
    m = np.round(tau / tau0)
    gm = sum(allan_var_gm(m, tau0, tc, gm_q2) for tc in TAU_C_S) if gm_q2 > 0 else 0 * tau
    return {'white': n_density**2 / tau,
            'random_walk': k_rw**2 * tau / 3 + k_rw**2 * tau0**2 / (6 * tau),
            'bias_instability': gm,
            'quantisation': 3 * q_coeff**2 / tau**2}


def gm_variance_for(b_coeff, tau0):
    """q^2 of each Gauss-Markov process giving bias instability B, and the ripple
    (max/min of the Allan deviation over PLATEAU_S)."""
    tau = np.logspace(math.log10(PLATEAU_S[0]), math.log10(PLATEAU_S[1]), 41)
    unit = np.sqrt(allan_var_terms(tau, tau0, 0, 0, 1.0, 0)['bias_instability'])
    q2 = (FLICKER_FACTOR * b_coeff / float(np.median(unit)))**2
    return q2, float(unit.max() / unit.min())


class Axis:
    """Streams one axis: constant + white + random walk + Gauss-Markov sum, optionally quantised.

    next(n) returns (total, parts) with parts the white, random-walk and
    bias-instability components (before quantisation) for the self-check.
    """

    def __init__(self, rng, rate_hz, constant, n_density, k_rw, b_coeff, q_coeff):
        self.rng, self.tau0 = rng, 1.0 / rate_hz
        self.constant, self.sigma_white = constant, n_density * math.sqrt(rate_hz)
        self.sigma_step = k_rw * math.sqrt(self.tau0)
        self.q2, self.ripple = gm_variance_for(b_coeff, self.tau0) if b_coeff > 0 else (0.0, 1.0)
        self.phis = [math.exp(-self.tau0 / tc) for tc in TAU_C_S]
        self.gm_state = [rng.normal(0, math.sqrt(self.q2)) for _ in TAU_C_S]   # stationary start
        self.gm_tail = [None for _ in TAU_C_S]
        self.rw_state = 0.0
        self.q_step = math.sqrt(12) * q_coeff
        self.theta = 0.0
        self.theta_rounded = 0.0

    def _gm(self, j, n):
        phi, out = self.phis[j], np.empty(n)
        drive = self.rng.standard_normal(n) * math.sqrt(self.q2 * (1 - phi * phi))
        taps = int(math.ceil(37.0 / max(-math.log(phi), 1e-300)))   # phi^taps < 1e-16
        if taps <= CONVOLVE_MAX:
            # Short memory: x_n = sum_{i<taps} phi^i d_{n-i} (the older drives
            # weigh below 1e-16), as one convolution over the previous chunk's
            # last drives and this chunk's.
            tail = self.gm_tail[j]
            if tail is None:   # stationary start: taps drives before the first sample
                tail = self.rng.standard_normal(taps) * math.sqrt(self.q2 * (1 - phi * phi))
            ext = np.concatenate([tail, drive])
            out = np.convolve(ext, phi ** np.arange(taps))[len(tail):len(tail) + n]
            self.gm_tail[j] = ext[-taps:]
            return out
        block = max(1, int(SAFE_EXPONENT / max(-math.log(phi), 1e-300)))
        x = self.gm_state[j]
        for s in range(0, n, block):
            d = drive[s:s + block]
            pw = phi ** np.arange(1, len(d) + 1)
            seg = pw * (x + np.cumsum(d / pw))
            out[s:s + len(d)] = seg
            x = seg[-1]
        self.gm_state[j] = x
        return out

    def next(self, n):
        white = self.rng.standard_normal(n) * self.sigma_white
        steps = self.rng.standard_normal(n) * self.sigma_step
        rw = self.rw_state + np.cumsum(steps)
        self.rw_state = rw[-1]
        bi = sum(self._gm(j, n) for j in range(len(TAU_C_S))) if self.q2 > 0 else np.zeros(n)
        y = self.constant + white + rw + bi
        if self.q_step > 0:
            theta = self.theta + np.cumsum(y) * self.tau0
            rounded = np.round(theta / self.q_step) * self.q_step
            y = np.diff(np.concatenate([[self.theta_rounded], rounded])) / self.tau0
            self.theta, self.theta_rounded = theta[-1], rounded[-1]
        return y, {'white': white, 'steps': steps, 'bias_instability': bi}
