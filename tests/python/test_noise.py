"""mpcal.noise on arrays gives what `mpcal noise --json` writes for the same
still record, and its Allan deviation is the IEEE Std 952 formula."""
import json

import numpy as np
import pytest

import mpcal
from conftest import run_mpcal


@pytest.fixture(scope="module")
def still(tmp_path_factory):
    d = tmp_path_factory.mktemp("still")
    run_mpcal("simulate", "noise", "--preset", "consumer", "--hours", "0.25", "--seed", "1",
              "-o", "still.csv", "--truth", "truth.json", cwd=d)
    run_mpcal("noise", "still.csv", "--json", "noise.json", cwd=d)
    return (mpcal.read_log(d / "still.csv"), json.loads((d / "noise.json").read_text()),
            json.loads((d / "truth.json").read_text()))


@pytest.fixture(scope="module")
def result(still):
    rec, _, _ = still
    return mpcal.noise(rec.t, rec.accel, rec.gyro)


def test_terms_and_curves_equal_the_commands(still, result):
    _, cli, _ = still
    assert result.format == cli["format"]
    assert result.samples == cli["samples"]
    for sensor, key in (("accelerometer", "white_noise_mps2_per_rthz"),
                        ("gyroscope", "white_noise_radps_per_rthz")):
        for axis in "xyz":
            py, c = result[sensor].axes[axis], cli[sensor]["axes"][axis]
            assert py[key].status == c[key]["status"] == "measured"
            assert py[key].value == pytest.approx(c[key]["value"], rel=1e-9)
            allan = py.allan
            np.testing.assert_allclose(allan.tau_s, c["allan"]["tau_s"], rtol=1e-12)
            curve = "adev_mps2" if sensor == "accelerometer" else "adev_radps"
            np.testing.assert_allclose(allan[curve], c["allan"][curve], rtol=1e-9)


def overlapping_adev(y, rate_hz, m, stride):
    """IEEE Std 952-1997 (C.2), the overlapping Allan deviation at τ = m τ0
    of rate samples y, from the phase x_k = τ0 Σ y, over the start indices
    k = 0, stride, 2 stride, ... (stride 1: every one; mpcal thins the
    starts of the long clusters, noise.h's AllanPoint::stride):
    σ²(τ) = Σ_k (x_{k+2m} − 2 x_{k+m} + x_k)² / (2 τ² K)."""
    tau0 = 1.0 / rate_hz
    x = np.concatenate([[0.0], np.cumsum(y) * tau0])
    d = (x[2 * m:] - 2 * x[m:-m] + x[:-2 * m])[::stride]
    tau = m * tau0
    return np.sqrt(np.sum(d * d) / (2 * tau * tau * len(d)))


def test_allan_deviation_is_the_standards_formula(still, result):
    rec, _, _ = still
    allan = result.accelerometer.axes.x.allan
    y = rec.accel[:, 0] - rec.accel[:, 0].mean()  # the mean, for the phase's rounding
    for k in range(0, len(allan.tau_s), 7):
        m, stride = int(allan.m[k]), int(allan.stride[k])
        assert allan.tau_s[k] == pytest.approx(m / result.rate_hz, rel=1e-12)
        assert allan.adev_mps2[k] == pytest.approx(
            overlapping_adev(y, result.rate_hz, m, stride), rel=1e-9)


def test_white_noise_is_the_truths(still, result):
    # The white noise is measured to better than 1 % (its interval) on a
    # quarter of an hour; the simulation's truth lies within 5 % on every axis.
    _, _, truth = still
    for i, axis in enumerate("xyz"):
        value = result.accelerometer.axes[axis].white_noise_mps2_per_rthz.value
        true = truth["accelerometer"]["white_noise_mps2_per_rthz"][i]
        assert value == pytest.approx(true, rel=0.05)


def test_raw_counts_have_no_noise_unit():
    t = np.arange(1000) / 100.0
    with pytest.raises(mpcal.Error) as caught:
        mpcal.noise(t, np.full((1000, 3), 32768.0), units="counts")
    assert caught.value.kind == "units"


def test_simulate_noise_equals_the_commands_record(still):
    rec, _, truth = still
    simulated, true = mpcal.simulate_noise("consumer", duration_s=900, rate_hz=100, seed=1)
    assert len(simulated) == len(rec)
    # The command writes 9 significant digits: half a unit of the last.
    np.testing.assert_allclose(simulated.accel, rec.accel, rtol=5.01e-9, atol=0)
    np.testing.assert_allclose(simulated.gyro, rec.gyro, rtol=5.01e-9, atol=0)
    np.testing.assert_allclose(true["accelerometer"]["white_noise_mps2_per_rthz"],
                               truth["accelerometer"]["white_noise_mps2_per_rthz"], rtol=1e-15)


def test_arrays_of_the_callers_are_read_in_place_and_give_the_commands(still, result):
    # Copies of the record's rows (arrays of the caller's: read where they
    # are, not the Recording's), the gyroscope also in deg/s (converted into
    # rows of the module's own): the command's terms, the arrays unwritten.
    rec, cli, _ = still
    t, accel, gyro = np.array(rec.t), np.array(rec.accel), np.array(rec.gyro)
    gyro_dps = np.degrees(gyro)
    kept = [a.copy() for a in (t, accel, gyro, gyro_dps)]
    for g, units in ((gyro, "rads"), (gyro_dps, "dps")):
        mine = mpcal.noise(t, accel, g, gyro_units=units)
        assert mine.samples == cli["samples"]
        for sensor, key in (("accelerometer", "white_noise_mps2_per_rthz"),
                            ("gyroscope", "white_noise_radps_per_rthz")):
            for axis in "xyz":
                # deg/s to rad/s and back changes the last bit of some readings.
                assert mine[sensor].axes[axis][key].value == pytest.approx(
                    cli[sensor]["axes"][axis][key]["value"], rel=1e-9)
    for a, k in zip((t, accel, gyro, gyro_dps), kept):
        np.testing.assert_array_equal(a, k)


def test_a_nan_is_refused_naming_the_argument_and_row(still):
    rec, _, _ = still
    accel, gyro = np.array(rec.accel), np.array(rec.gyro)
    gyro[20000, 2] = np.nan
    with pytest.raises(mpcal.Error, match=r"^gyro: row 20000 is not finite") as caught:
        mpcal.noise(rec.t, accel, gyro)
    assert caught.value.kind == "input"
    accel[31, 0] = -np.inf
    with pytest.raises(mpcal.Error, match=r"^accel: row 31 is not finite"):
        mpcal.noise(rec.t, accel, whole=True)
