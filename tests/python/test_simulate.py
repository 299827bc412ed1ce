"""A simulated session with known errors: the calibration finds them within
its 1σ; a long call is interrupted by Ctrl-C; the GIL is released."""
import gc
import os
import signal
import sys
import threading
import time

import numpy as np
import pytest

import mpcal


@pytest.fixture(scope="module")
def session():
    return mpcal.simulate_static(seed=3)


def test_the_simulation_is_what_was_asked(session):
    # 10 s rest + 26 × (2 s turn + 10 s still) at the MTi-G's 512 Hz.
    assert session.rate_hz == 512
    assert len(session.t) == pytest.approx((10 + 26 * 12) * 512, abs=2)
    assert session.accel.shape == (len(session.t), 3)
    assert session.still_ranges.shape == (26, 2)
    np.testing.assert_allclose(np.linalg.norm(session.directions, axis=1), 1, rtol=1e-12)
    # At rest the truth's correction gives gravity along the direction, up to
    # the noise averaged over the position (σ/√n, here about 0.5 mm/s²).
    for (begin, end), d in zip(session.still_ranges, session.directions):
        a, _ = session.truth.correct(session.accel[begin:end])
        n = end - begin
        np.testing.assert_allclose(a.mean(axis=0), 9.80665 * d,
                                   atol=5 * session.noise_std_mps2.max() / np.sqrt(n))


def test_calibration_finds_the_truth_within_its_std(session):
    cal = mpcal.calibrate(session.t, session.accel)
    assert cal.fit.positions == 27  # the 26 and the initial rest, still too
    z_bias = (cal.bias_mps2 - session.truth.bias_mps2) / cal.std.bias_mps2
    z_scale = ((cal.scale_factor_error - session.truth.scale_factor_error) /
               cal.std.scale_factor_error)
    # Nine standard normal z if the 1σ are honest: |z| < 4.5 fails by chance
    # once in about 16,000 sessions.
    assert np.all(np.abs(z_bias) < 4.5), z_bias
    assert np.all(np.abs(z_scale) < 4.5), z_scale
    for k in ("yz", "zx", "zy"):
        z = ((cal.non_orthogonality_rad[k] - session.truth.non_orthogonality_rad[k]) /
             cal.std.non_orthogonality_rad[k])
        assert abs(z) < 4.5, (k, z)


def test_unknown_preset():
    with pytest.raises(mpcal.Error, match="colibri"):
        mpcal.simulate_static(preset="no-such-device")


def test_ctrl_c_interrupts_a_long_calibration():
    # 1.7 M rows (1 kHz, 26 positions of 60 s): about 70 ms of work on a
    # 2-core machine, several times that when it is loaded.
    long = mpcal.simulate_static(seed=1, rate_hz=1000, dwell_s=60, initial_rest_s=88)
    started = time.monotonic()
    mpcal.calibrate(long.t, long.accel)
    whole_s = time.monotonic() - started
    # Ctrl-C a twentieth into the call: the KeyboardInterrupt comes well
    # before the call would have ended (were it raised only after the call
    # returned, as without the check, the wait would be the whole call). The
    # call looks for signals every 50 ms (python/interrupt.h), two thirds of
    # this call on an idle machine, so the bound is 0.9 of the call. A shared
    # machine can stall any one try, so the best of three counts.
    waits = []
    for _ in range(3):
        timer = threading.Timer(0.05 * whole_s, os.kill, (os.getpid(), signal.SIGINT))
        started = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            mpcal.calibrate(long.t, long.accel)
        waits.append(time.monotonic() - started)
        timer.join()
    assert min(waits) < 0.9 * whole_s, (waits, whole_s)


def test_arrays_read_in_place_outlive_an_interrupted_call():
    # Arrays of the caller's are read where they are: a call that Ctrl-C
    # interrupted goes on reading them on its thread, so the module holds
    # them until it ends, and lets them go then.
    long = mpcal.simulate_static(seed=1, rate_hz=1000, dwell_s=60, initial_rest_s=88)
    t, accel = np.array(long.t), np.array(long.accel)
    started = time.monotonic()
    expected = mpcal.calibrate(t, accel).bias_mps2
    whole_s = time.monotonic() - started
    refs = sys.getrefcount(accel)
    timer = threading.Timer(0.2 * whole_s, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        mpcal.calibrate(t, accel)
    timer.join()
    # The caller frees the memory (numpy gives arrays this large back to the
    # system: a read of them after would crash) while the work may still
    # read it.
    probe = accel
    del t, accel
    gc.collect()
    scratch = [np.full((len(long.t), 3), np.nan) for _ in range(2)]
    deadline = time.monotonic() + 60
    while sys.getrefcount(probe) > refs and time.monotonic() < deadline:
        time.sleep(0.01)  # the main thread's pending calls let the arrays go
    assert sys.getrefcount(probe) == refs
    del scratch
    # And the module works on after it.
    np.testing.assert_allclose(mpcal.calibrate(long.t, probe).bias_mps2, expected,
                               rtol=1e-9)


def test_other_threads_run_during_a_calibration():
    # With the GIL held for the whole call, the counter would not move. The
    # 1.7 M-row session (about 70 ms) gives it time for dozens of ticks.
    session = mpcal.simulate_static(seed=1, rate_hz=1000, dwell_s=60, initial_rest_s=88)
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    before = len(ticks)
    mpcal.calibrate(session.t, session.accel)
    during = len(ticks) - before
    stop.set()
    counter.join()
    assert during > 5
