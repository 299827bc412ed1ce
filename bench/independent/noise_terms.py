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
The effects of real sensors the IEEE model lacks (each optional):
  low-pass  the white noise through a first-order IIR low-pass of bandwidth
     F (-3 dB), y_n = a y_(n-1) + (1 - a) x_n with a = exp(-2 pi F tau0), as
     a MEMS digital low-pass filter: unit gain at DC, so the density at low
     frequency stays N.  The output is an AR(1) sequence with phi = a and
     variance N^2 rate (1 - a) / (1 + a), so its Allan variance is the
     Gauss-Markov formula below with tau_c = 1 / (2 pi F).
  bump  one first-order Gauss-Markov process of standard deviation sigma and
     correlation time tau_c (x_n = phi x_(n-1) + w_n, phi = exp(-tau0 /
     tau_c)): its Allan deviation rises as sqrt(tau), peaks at about 0.62
     sigma near tau = 1.9 tau_c and falls as 1/sqrt(tau) (IEEE 952 C.1.6).
  sine  A sin(2 pi t / P + phase), the phase drawn per axis: the cluster
     means of m samples scale its amplitude by sin(m w)/(m sin w), w = pi
     tau0 / P, and two of them m samples apart differ by 2 sin(m w) of it, so
     averaged over the phase the Allan variance is exactly
     A^2 sin^4(m w) / (m^2 sin^2 w) (IEEE 952 C.1.7: A^2 (sin^2(pi tau /
     P) / (pi tau / P))^2 as tau0 -> 0).
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


def lowpass_phi(lowpass_hz, tau0):
    """a of the first-order IIR low-pass of bandwidth lowpass_hz (0: no filter)."""
    return math.exp(-2 * math.pi * lowpass_hz * tau0) if lowpass_hz > 0 else 0.0


def allan_var_sine(m, tau0, amplitude, period_s):
    w = math.pi * tau0 / period_s
    m = np.asarray(m, float)
    return amplitude**2 * np.sin(m * w)**4 / (m * m * math.sin(w)**2)


def allan_var_terms(tau, tau0, n_density, k_rw, gm_q2, q_coeff, lowpass_hz=0.0,
                    bump=(0.0, 1.0), sine=(0.0, 1.0)):
    """Dict of the Allan variance of each term at cluster times tau (multiples of tau0).

    lowpass_hz: the white noise's first-order low-pass (0: none); bump:
    (sigma, tau_c) of the Gauss-Markov bump; sine: (amplitude, period_s)."""
    tau = np.asarray(tau, float)
    m = np.round(tau / tau0)
    gm = sum(allan_var_gm(m, tau0, tc, gm_q2) for tc in TAU_C_S) if gm_q2 > 0 else 0 * tau
    white = n_density**2 / tau
    if lowpass_hz > 0:
        a = lowpass_phi(lowpass_hz, tau0)
        q2 = n_density**2 / tau0 * (1 - a) / (1 + a)
        white = allan_var_gm(m, tau0, -tau0 / math.log(a), q2)
    out = {'white': white,
           'random_walk': k_rw**2 * tau / 3 + k_rw**2 * tau0**2 / (6 * tau),
           'bias_instability': gm,
           'quantisation': 3 * q_coeff**2 / tau**2}
    if bump[0] > 0:
        out['bump'] = allan_var_gm(m, tau0, bump[1], bump[0]**2)
    if sine[0] > 0:
        out['sine'] = allan_var_sine(m, tau0, sine[0], sine[1])
    return out


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

    def __init__(self, rng, rate_hz, constant, n_density, k_rw, b_coeff, q_coeff,
                 lowpass_hz=0.0, bump=(0.0, 1.0), sine=(0.0, 1.0)):
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
        # The extra effects are set up (and draw from rng) only when asked
        # for, so that a seed without them gives the same file as always.
        self.ar1 = []   # (phi, drive sigma) of the low-pass [0] and the bump [1]
        self.lowpass = lowpass_hz > 0
        if self.lowpass:
            a = lowpass_phi(lowpass_hz, self.tau0)
            self.ar1.append((a, None))
        self.bump = bump[0] > 0
        if self.bump:
            phi = math.exp(-self.tau0 / bump[1])
            self.ar1.append((phi, bump[0] * math.sqrt(1 - phi * phi)))
        for phi, _ in self.ar1:
            self.phis.append(phi)
            self.gm_state.append(0.0)
            self.gm_tail.append(None)
        if self.lowpass:   # stationary start of the filter: its output's variance
            self.gm_state[len(TAU_C_S)] = rng.normal(0, self.sigma_white * math.sqrt((1 - a) / (1 + a)))
        if self.bump:
            self.gm_state[-1] = rng.normal(0, bump[0])
        self.sine = sine
        self.sine_phase = rng.uniform(0, 2 * math.pi) if sine[0] > 0 else 0.0
        self.sample = 0

    def _gm(self, j, n, drive=None, drive_sigma=None):
        """n samples of the AR(1) j: x_n = phi x_(n-1) + d_n, the drives d
        given (the low-pass: (1 - a) times the white samples) or drawn with
        standard deviation drive_sigma (default: a bias-instability process)."""
        phi, out = self.phis[j], np.empty(n)
        if drive_sigma is None:
            drive_sigma = math.sqrt(self.q2 * (1 - phi * phi))
        if drive is None:
            drive = self.rng.standard_normal(n) * drive_sigma
        taps = int(math.ceil(37.0 / max(-math.log(phi), 1e-300)))   # phi^taps < 1e-16
        if taps <= CONVOLVE_MAX:
            # Short memory: x_n = sum_{i<taps} phi^i d_{n-i} (the older drives
            # weigh below 1e-16), as one convolution over the previous chunk's
            # last drives and this chunk's.
            tail = self.gm_tail[j]
            if tail is None:   # stationary start: taps drives before the first sample
                tail = self.rng.standard_normal(taps) * drive_sigma
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
        j = len(TAU_C_S)
        heard = white
        if self.lowpass:
            a = self.phis[j]
            heard = self._gm(j, n, drive=(1 - a) * white, drive_sigma=(1 - a) * self.sigma_white)
            j += 1
        y = self.constant + heard + rw + bi
        if self.bump:
            y = y + self._gm(j, n, drive_sigma=self.ar1[-1][1])
        if self.sine[0] > 0:
            t = (self.sample + np.arange(n)) * self.tau0
            y = y + self.sine[0] * np.sin(2 * math.pi * t / self.sine[1] + self.sine_phase)
        self.sample += n
        if self.q_step > 0:
            theta = self.theta + np.cumsum(y) * self.tau0
            rounded = np.round(theta / self.q_step) * self.q_step
            y = np.diff(np.concatenate([[self.theta_rounded], rounded])) / self.tau0
            self.theta, self.theta_rounded = theta[-1], rounded[-1]
        return y, {'white': white, 'steps': steps, 'bias_instability': bi}
