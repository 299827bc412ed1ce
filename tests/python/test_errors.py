"""Bad input raises mpcal.Error with its kind, advice as keyword arguments,
and a message that names the argument; findings come as warnings."""
import numpy as np
import pytest

import mpcal
from conftest import XSENS_ACC, XSENS_GRAVITY_MPS2

G = 9.80665


def still_positions(n_positions=12, seconds=6.0, rate_hz=100.0, scale=1.0, seed=1):
    """A session of still positions joined by ramps, written here from the
    forward model with no error: gravity along spread directions, white
    noise of 0.01 m/s² (1σ)."""
    rng = np.random.default_rng(seed)
    dirs = rng.normal(size=(n_positions, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    per = int(seconds * rate_hz)
    ramp = int(rate_hz)
    rows = []
    for i, d in enumerate(dirs):
        rows.append(np.tile(d * G, (per, 1)))
        if i + 1 < n_positions:
            w = np.linspace(0, 1, ramp)[:, None]
            m = (1 - w) * d + w * dirs[i + 1]
            rows.append(m / np.linalg.norm(m, axis=1, keepdims=True) * G)
    accel = np.vstack(rows) + rng.normal(scale=0.01, size=(sum(len(r) for r in rows), 3))
    t = np.arange(len(accel)) / rate_hz
    return t, accel * scale


def test_error_is_a_value_error_with_kind_and_advice():
    t, accel = still_positions()
    with pytest.raises(mpcal.Error) as caught:
        # Readings in m/s² declared as g: the library says they look like m/s².
        mpcal.calibrate(t, accel, units="g")
    e = caught.value
    assert isinstance(e, ValueError)
    assert e.kind == "units"
    assert e.advice == {"units": "mps2"}
    assert e.figures["looks_like"] == "mps2"
    assert e.figures["median_magnitude"] == pytest.approx(G, rel=0.01)
    assert "--" not in str(e)  # no command-line flag in the Python message


def test_readings_in_g_declared_as_mps2():
    t, accel = still_positions(scale=1 / G)
    with pytest.raises(mpcal.Error) as caught:
        mpcal.calibrate(t, accel)
    assert caught.value.kind == "units"
    assert caught.value.advice == {"units": "g"}


def test_a_session_that_never_stops_moving():
    t = np.arange(3000) / 100.0
    angle = 0.5 * t  # rad: turning at 0.5 rad/s throughout
    accel = G * np.column_stack([np.cos(angle), np.sin(angle), np.zeros_like(t)])
    with pytest.raises(mpcal.Error) as caught:
        mpcal.calibrate(t, accel)
    e = caught.value
    assert e.kind == "session"
    assert e.figures["problem"] == "no_positions"
    assert e.figures["positions"] == 0


def test_the_simulated_session_calibrates_to_zero_errors():
    # The same generator gives a good session: the errors are zero within
    # their 1σ (5σ, as a check that cannot fail by chance more than rarely).
    t, accel = still_positions(n_positions=20)
    cal = mpcal.calibrate(t, accel)
    assert np.all(np.abs(cal.bias_mps2) < 5 * cal.std.bias_mps2 + 1e-9)
    assert np.all(np.abs(cal.scale_factor_error) < 5 * cal.std.scale_factor_error + 1e-12)


@pytest.mark.parametrize("accel, words", [
    (np.zeros((10, 2)), ["accel", "shape (10, 2)", "(N, 3)"]),
    (np.zeros(10), ["accel", "shape (10,)"]),
    (np.array([["a", "b", "c"]] * 10), ["accel", "dtype"]),
    (np.zeros((10, 3), dtype=complex), ["accel", "dtype complex128"]),
])
def test_arrays_of_the_wrong_shape_or_dtype(accel, words):
    with pytest.raises(mpcal.Error) as caught:
        mpcal.calibrate(np.arange(10.0), accel)
    assert caught.value.kind == "input"
    for w in words:
        assert w in str(caught.value)


def test_nan_is_refused_naming_the_argument_and_row():
    t, accel = still_positions()
    gyro = np.zeros_like(accel)
    gyro[7, 1] = np.nan
    with pytest.raises(mpcal.Error, match=r"gyro: row 7 is not finite"):
        mpcal.calibrate(t, accel, gyro)
    t[3] = np.inf
    with pytest.raises(mpcal.Error, match=r"^t: row 3 is not finite"):
        mpcal.calibrate(t, accel)


def test_nan_is_refused_by_detect_naming_the_argument_and_row():
    t, accel = still_positions()
    accel[4321, 2] = np.nan
    with pytest.raises(mpcal.Error, match=r"^accel: row 4321 is not finite") as caught:
        mpcal.detect(t, accel)
    assert caught.value.kind == "input"
    assert caught.value.figures == {"argument": "accel", "row": 4321, "rows": 1}
    t[5] = np.nan
    with pytest.raises(mpcal.Error, match=r"^t: row 5 is not finite"):
        mpcal.detect(t, accel)


def test_arrays_of_different_lengths():
    t, accel = still_positions()
    with pytest.raises(mpcal.Error, match=r"t has 100, accel has"):
        mpcal.calibrate(t[:100], accel)


def test_options_out_of_range_and_unknown():
    t, accel = still_positions()
    with pytest.raises(mpcal.Error) as caught:
        mpcal.calibrate(t, accel, window_s=-1.0)
    assert caught.value.kind == "option"
    with pytest.raises(mpcal.Error, match="units='furlongs'") as caught:
        mpcal.calibrate(t, accel, units="furlongs")
    assert caught.value.advice == {"units": None}
    with pytest.raises(mpcal.Error, match="gravity or latitude_deg"):
        mpcal.calibrate(t, accel, gravity=9.81, latitude_deg=45.0)
    with pytest.raises(TypeError, match="windw_s"):
        mpcal.calibrate(t, accel, windw_s=1.0)


def test_files_that_cannot_be_read(tmp_path):
    with pytest.raises(mpcal.Error) as caught:
        mpcal.read_log(tmp_path / "missing.csv")
    assert caught.value.kind == "io"
    assert "missing.csv" in str(caught.value)
    bad = tmp_path / "bad.csv"
    bad.write_text("t,ax,ay,az\n0,1,2,3\n0.01,1,x,3\n0.02,1,2,3\n")
    with pytest.raises(mpcal.Error, match=r"bad.csv:3: .*column 'ay'"):
        mpcal.read_log(bad)
    other = tmp_path / "other.json"
    other.write_text('{"format": "something/1"}\n')
    with pytest.raises(mpcal.Error) as caught:
        mpcal.load_calibration(other)
    assert caught.value.kind == "format"


def test_save_refuses_a_directory(tmp_path):
    rec = mpcal.read_log(XSENS_ACC, units="counts")
    cal = mpcal.calibrate(rec.t, rec.accel, units="counts", gravity=XSENS_GRAVITY_MPS2)
    with pytest.raises(mpcal.Error) as caught:
        cal.save(tmp_path)
    assert caught.value.kind in ("io", "input")


def test_reader_findings_are_warnings(tmp_path):
    log = tmp_path / "dup.csv"
    rows = ["t,ax,ay,az"] + [f"{i / 100:.2f},0,0,9.8" for i in range(50)]
    rows.insert(10, rows[10])  # a duplicated time
    log.write_text("\n".join(rows) + "\n")
    with pytest.warns(mpcal.MpcalWarning, match="duplicate"):
        rec = mpcal.read_log(log)
    assert len(rec) == 50
    assert any("duplicate" in w for w in rec.warnings)


def test_exceptions_inside_the_library_after_other_extensions_loaded(tmp_path):
    # libstdc++ loaded first by another extension (matplotlib's, in C++):
    # the library's own exceptions, thrown and caught inside it (the reader
    # asks whether a text file is a bag), must unwind with the same unwinder.
    import subprocess
    import sys
    pytest.importorskip("matplotlib._path")
    code = ("import matplotlib._path; import mpcal; "
            f"r = mpcal.read_log({str(XSENS_ACC)!r}, units='counts'); print(len(r))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "51175"


def test_advice_taken_as_keyword_arguments_calibrates():
    # Nine faces and edges held within 1 deg: the angles are not determined,
    # and the library says which model would do.
    s = mpcal.simulate_static(seed=4, positions=9, tilt_deg=1)
    with pytest.raises(mpcal.Error) as caught:
        mpcal.calibrate(s.t, s.accel)
    e = caught.value
    assert e.kind == "session"
    assert "theta_zy_rad" in str(e)
    assert e.advice == {"model": "bias-scale-6"}
    cal = mpcal.calibrate(s.t, s.accel, **e.advice)
    assert cal.model == "bias-scale-6"
    z = (cal.bias_mps2 - s.truth.bias_mps2) / cal.std.bias_mps2
    # The truth's angles are small (0.01-0.18 mrad): the six-parameter
    # model's biases are the truth's within their 1σ (|z| < 4.5: a chance
    # failure once in about 50,000 sessions).
    assert np.all(np.abs(z) < 4.5), z
