"""mpcal.calibrate on numpy arrays gives the numbers `mpcal calibrate` writes
for the same recording, and correct() is the model of docs/method.md §2."""
import json
import math

import numpy as np
import pytest

import mpcal
from conftest import XSENS_ACC, XSENS_GRAVITY_MPS2, XSENS_GYRO, run_mpcal

# The same library code on the same doubles (the reader's rows, handed over
# as arrays and back without conversion): the results are equal but for
# the last bits that the order of the solver's threads may change.
RTOL = 1e-9


@pytest.fixture(scope="module")
def cli_accel(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli_accel")
    run_mpcal("calibrate", XSENS_ACC, "--units", "counts", "--gravity",
              XSENS_GRAVITY_MPS2, "-o", "calib.json", cwd=d)
    return json.loads((d / "calib.json").read_text())


@pytest.fixture(scope="module")
def cli_imu(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli_imu")
    run_mpcal("calibrate", XSENS_ACC, "--gyro-log", XSENS_GYRO, "--units", "counts",
              "--gyro-units", "counts", "--gravity", XSENS_GRAVITY_MPS2, "-o", "imu.json",
              cwd=d)
    return json.loads((d / "imu.json").read_text())


@pytest.fixture(scope="module")
def recording():
    return mpcal.read_log(XSENS_ACC, units="counts")


@pytest.fixture(scope="module")
def cal(recording):
    return mpcal.calibrate(recording.t, recording.accel, units="counts",
                           gravity=XSENS_GRAVITY_MPS2)


def test_read_log_gives_the_rows_as_arrays(recording):
    raw = np.loadtxt(XSENS_ACC)  # the file itself: t, x, y, z in counts
    assert recording.units == "counts"
    assert recording.gyro is None
    assert recording.accel.shape == (len(raw), 3)
    np.testing.assert_array_equal(recording.t, raw[:, 0])
    np.testing.assert_array_equal(recording.accel, raw[:, 1:])
    assert not recording.accel.flags.writeable


def assert_model_equal(py, cli):
    np.testing.assert_allclose(py.bias_mps2, cli["bias_mps2"], rtol=RTOL, atol=0)
    np.testing.assert_allclose(py.scale_factor_error, cli["scale_factor_error"],
                               rtol=RTOL, atol=0)
    for k in ("yz", "zx", "zy"):
        assert py.non_orthogonality_rad[k] == pytest.approx(
            cli["non_orthogonality_rad"][k], rel=RTOL, abs=0)


def test_parameters_and_std_equal_the_commands(cal, cli_accel):
    assert cal.format == cli_accel["format"] == "mpcal.accelerometer/1"
    assert_model_equal(cal, cli_accel)
    assert_model_equal(cal.std, cli_accel["std"])
    assert cal.input.mps2_per_unit == pytest.approx(cli_accel["input"]["mps2_per_unit"],
                                                    rel=RTOL)
    assert cal.gravity_mps2 == XSENS_GRAVITY_MPS2
    assert cal.fit.positions == cli_accel["fit"]["positions"]
    assert cal.fit.variance_factor == pytest.approx(cli_accel["fit"]["variance_factor"],
                                                    rel=RTOL)
    assert len(cal.positions) == len(cli_accel["positions"])
    assert cal.split_half.widening == pytest.approx(
        cli_accel["fit"]["split_half"]["widening"], rel=RTOL)
    # Figures the Xsens session is known by (tests/cli/calibrate.cmake):
    # 38 positions, 1 g about 4000 counts.
    assert cal.fit.positions == 38
    assert 9.81744 / 4100 < cal.input.mps2_per_unit < 9.81744 / 4000


def test_imu_from_two_files_equals_the_commands(cli_imu):
    rec = mpcal.read_log(XSENS_ACC, units="counts", gyro_log=str(XSENS_GYRO),
                         gyro_units="counts")
    assert rec.gyro.shape == rec.accel.shape
    imu = mpcal.calibrate(rec.t, rec.accel, rec.gyro, units="counts",
                          gyro_units="counts", gravity=XSENS_GRAVITY_MPS2)
    assert imu.format == "mpcal.imu/1"
    assert_model_equal(imu, cli_imu)
    g, cli_g = imu.gyroscope, cli_imu["gyroscope"]
    np.testing.assert_allclose(g.m, np.asarray(cli_g["m"]).reshape(g.m.shape),
                               rtol=RTOL, atol=1e-15)
    np.testing.assert_allclose(g.bias_radps, cli_g["bias_radps"], rtol=RTOL, atol=1e-15)
    np.testing.assert_allclose(g.std.bias_radps, cli_g["std"]["bias_radps"], rtol=RTOL)
    assert g.input.radps_per_unit == pytest.approx(cli_g["input"]["radps_per_unit"],
                                                   rel=RTOL)

    # The gyroscope's correction, written from the IMU file's fields
    # (docs/formats.md): ω = M (r k − b − G f), f the corrected specific force.
    a_mps2, w_radps = imu.correct(rec.accel, rec.gyro)
    m = np.asarray(cli_g["m"]).reshape(3, 3)
    b = np.asarray(cli_g["bias_radps"])
    k = cli_g["input"]["radps_per_unit"]
    g_sens = np.asarray(cli_g.get("g_sensitivity_radps_per_mps2", np.zeros(9))).reshape(3, 3)
    expected = (rec.gyro * k - b - a_mps2 @ g_sens.T) @ m.T
    np.testing.assert_allclose(w_radps, expected, rtol=1e-9, atol=1e-12)


def method_correction(p, y_mps2):
    """docs/method.md §2.1, eqs 8-10, written out: a = T diag(1/(1+s)) (Y - b)."""
    b = np.asarray(p["bias_mps2"])
    s = np.asarray(p["scale_factor_error"])
    yz, zx, zy = (p["non_orthogonality_rad"][k] for k in ("yz", "zx", "zy"))
    d = y_mps2 - b
    ax = d[:, 0] / (1 + s[0])
    ay = ax * math.tan(yz) + d[:, 1] / ((1 + s[1]) * math.cos(yz))
    az = (-ax * math.tan(zy) / math.cos(zx) + ay * math.tan(zx) +
          d[:, 2] / ((1 + s[2]) * math.cos(zx) * math.cos(zy)))
    return np.column_stack([ax, ay, az])


def test_correct_is_the_method_and_brings_the_positions_to_gravity(cal, recording,
                                                                   cli_accel):
    corrected, gyro = cal.correct(recording.accel)
    assert gyro is None
    k = cli_accel["input"]["mps2_per_unit"]
    expected = method_correction(cli_accel, recording.accel * k)
    np.testing.assert_allclose(corrected, expected, rtol=1e-12, atol=1e-12)
    # At each static position the corrected magnitude is gravity, within the
    # position's residual as the file states it.
    for p in cal.positions:
        a = method_correction(cli_accel, p.mean_mps2[None, :])[0]
        assert np.linalg.norm(a) - XSENS_GRAVITY_MPS2 == pytest.approx(
            p.residual_after_mps2, abs=1e-9)
        assert abs(p.residual_after_mps2) < 0.02  # m/s²: about 2 mg at most


def test_save_and_load_round_trip(cal, tmp_path):
    path = tmp_path / "xsens.json"
    cal.save(path)
    loaded = mpcal.load_calibration(path)
    assert json.loads(path.read_text())["format"] == "mpcal.accelerometer/1"
    np.testing.assert_array_equal(loaded.bias_mps2, cal.bias_mps2)
    np.testing.assert_array_equal(loaded.std.scale_factor_error, cal.std.scale_factor_error)
    assert loaded.provenance.input == "<arrays>"
    assert "units='counts'" in loaded.provenance.options
    assert [p.name for p in tmp_path.iterdir()] == ["xsens.json"]  # no temporary left


def test_arrays_of_other_dtypes_give_the_same_result(recording, cal):
    # Integer counts (as many loggers give them) and a non-contiguous view.
    counts = recording.accel.astype(np.int32)
    np.testing.assert_array_equal(counts, recording.accel)
    other = mpcal.calibrate(recording.t, np.asfortranarray(counts), units="counts",
                            gravity=XSENS_GRAVITY_MPS2)
    np.testing.assert_allclose(other.bias_mps2, cal.bias_mps2, rtol=RTOL)


def misaligned(a):
    """A copy of `a` in memory one byte off the alignment of a double (an
    array made from a packed buffer)."""
    raw = bytearray(a.nbytes + 1)
    out = np.frombuffer(raw, dtype=np.float64, offset=1).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned and out.flags.c_contiguous
    return out


def test_arrays_of_the_callers_give_the_recordings_result(cli_imu):
    # Arrays of the caller's (copies: read in place, not the Recording's
    # rows), and the same values one byte off alignment (copied by the
    # module): both the numbers of the command.
    rec = mpcal.read_log(XSENS_ACC, units="counts", gyro_log=str(XSENS_GYRO),
                         gyro_units="counts")
    for make in (np.array, misaligned):
        t, accel, gyro = make(rec.t), make(rec.accel), make(rec.gyro)
        imu = mpcal.calibrate(t, accel, gyro, units="counts", gyro_units="counts",
                              gravity=XSENS_GRAVITY_MPS2)
        assert_model_equal(imu, cli_imu)
        g = imu.gyroscope
        np.testing.assert_allclose(g.m, np.asarray(cli_imu["gyroscope"]["m"]).reshape(
            g.m.shape), rtol=RTOL, atol=1e-15)
        # Read, never written.
        np.testing.assert_array_equal(accel, rec.accel)
        np.testing.assert_array_equal(gyro, rec.gyro)


def test_a_gyroscope_in_dps_is_converted_not_changed():
    s = mpcal.simulate_static(seed=3, gyro=True)
    t, accel, gyro = np.array(s.t), np.array(s.accel), np.array(s.gyro)
    in_radps = mpcal.calibrate(t, accel, gyro)
    gyro_dps = np.degrees(gyro)
    kept = gyro_dps.copy()
    in_dps = mpcal.calibrate(t, accel, gyro_dps, gyro_units="dps")
    np.testing.assert_array_equal(gyro_dps, kept)
    # rad/s to deg/s and back changes the last bit of some readings only.
    np.testing.assert_allclose(in_dps.gyroscope.m, in_radps.gyroscope.m, rtol=1e-9,
                               atol=1e-12)
    np.testing.assert_allclose(in_dps.gyroscope.bias_radps,
                               in_radps.gyroscope.bias_radps, rtol=1e-9, atol=1e-12)
    assert in_dps.gyroscope.input.units == "dps"


def test_detect_equals_the_commands_json(recording, tmp_path):
    run_mpcal("detect", XSENS_ACC, "--units", "counts", "--gravity", XSENS_GRAVITY_MPS2,
              "--json", "detect.json", cwd=tmp_path)
    cli = json.loads((tmp_path / "detect.json").read_text())
    d = mpcal.detect(recording.t, recording.accel, units="counts",
                     gravity=XSENS_GRAVITY_MPS2)
    assert d.format == "mpcal.detection/1"
    assert d.outcome.kind == "found"
    assert len(d.intervals) == len(cli["intervals"]) == 38
    for py, c in zip(d.intervals, cli["intervals"]):
        assert (py.begin, py.end, py.samples) == (c["begin"], c["end"], c["samples"])
        np.testing.assert_allclose(py.mean, c["mean"], rtol=RTOL)
        # The interval's mean is the mean of its rows (counts), computed here.
        np.testing.assert_allclose(py.mean, recording.accel[py.begin:py.end].mean(axis=0),
                                   rtol=1e-12)
    assert d.coverage.covered == cli["coverage"]["covered"]
    assert d.coverage.missing == cli["coverage"]["missing"]
    assert d.coverage.verdict == cli["coverage"]["verdict"] == "usable with warnings"


def test_detect_reads_the_callers_arrays_in_place(recording, tmp_path):
    # Copies of the reader's rows (arrays of the caller's: read where they
    # are, not the Recording's), and the same one byte off alignment (copied
    # by the module): the command's positions, the arrays unwritten.
    run_mpcal("detect", XSENS_ACC, "--units", "counts", "--gravity", XSENS_GRAVITY_MPS2,
              "--json", "detect.json", cwd=tmp_path)
    cli = json.loads((tmp_path / "detect.json").read_text())
    for make in (np.array, misaligned):
        t, accel = make(recording.t), make(recording.accel)
        d = mpcal.detect(t, accel, units="counts", gravity=XSENS_GRAVITY_MPS2)
        assert [(i.begin, i.end) for i in d.intervals] == \
            [(c["begin"], c["end"]) for c in cli["intervals"]]
        for py, c in zip(d.intervals, cli["intervals"]):
            np.testing.assert_allclose(py.mean, c["mean"], rtol=RTOL)
        assert d.detection.quiet_level == pytest.approx(cli["detection"]["quiet_level"],
                                                        rel=RTOL)
        np.testing.assert_array_equal(t, recording.t)
        np.testing.assert_array_equal(accel, recording.accel)


def test_detect_says_what_to_change_when_positions_are_too_short():
    # Four positions held 2.5 s, 1 s turns between them: too short for the
    # default minimum of 2 s once the window and the settling are trimmed.
    rng = np.random.default_rng(3)
    dirs = np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0], [0, 0, -1.0]])
    hold, turn, rate_hz = 250, 100, 100.0
    rows = []
    for i, d in enumerate(dirs):
        rows.append(np.tile(d * 9.80665, (hold, 1)))
        if i + 1 < len(dirs):
            w = np.linspace(0, 1, turn)[:, None]
            m = (1 - w) * d + w * dirs[i + 1]
            rows.append(m / np.linalg.norm(m, axis=1, keepdims=True) * 9.80665)
    accel = np.vstack(rows) + rng.normal(scale=0.005, size=(sum(map(len, rows)), 3))
    t = np.arange(len(accel)) / rate_hz
    d = mpcal.detect(t, accel)
    assert d.outcome.kind == "too_short"
    assert len(d.intervals) == 0
    assert 0 < d.outcome.advice["min_static_s"] < 2.0
    # The values the data suggest, taken, find the four positions, each
    # within its still stretch.
    suggested = {k: v for k, v in d.outcome.advice.items() if v is not None}
    found = mpcal.detect(t, accel, **suggested)
    assert found.outcome.kind == "found"
    assert len(found.intervals) == 4
    for i, interval in enumerate(found.intervals):
        start = i * (hold + turn) / rate_hz
        assert start <= interval.start_s < interval.end_s <= start + hold / rate_hz


@pytest.mark.parametrize("name", ["imu_lz4.bag", "imu_cdr_zstd.mcap", "imu_ros2"])
def test_bags_are_read_in_time_order(name):
    # Each holds the rows of session.csv as sensor_msgs/Imu on /imu/data,
    # written by python3-rosbag, @mcap/core or sqlite3 (tests/data/bags/),
    # with the stamps of rows 100 and 101 swapped: the reader puts them in
    # time order (row 101's readings first), says so, and gives the CSV's
    # rows otherwise.
    bags = XSENS_ACC.parents[2] / "bags"
    with pytest.warns(mpcal.MpcalWarning, match="1 message out of order"):
        recording = mpcal.read_log(bags / name, topic="/imu/data")
    rows = np.loadtxt(bags / "session.csv", delimiter=",", skiprows=1)
    rows[[100, 101], 1:] = rows[[101, 100], 1:]
    assert recording.accel.shape == (rows.shape[0], 3)
    np.testing.assert_allclose(recording.t, rows[:, 0] - rows[0, 0], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(recording.accel, rows[:, 1:4])
    with pytest.raises(mpcal.Error) as caught:
        mpcal.read_log(bags / name, topic="/no/such/topic")
    assert "/imu/data" in str(caught.value)  # the topics it has
