"""mpcal.export writes what `mpcal export` writes, byte for byte, for every
format of the registry; mpcal.import_calibration reads what `mpcal import`
reads."""
import json
import os
import subprocess
import warnings

import numpy as np
import pytest

import mpcal
from conftest import DATA, run_mpcal

HALF1 = DATA / "xsens_imu_half1.json"   # counts, with a gyroscope
MPS2 = DATA / "apply_calib.json"         # m/s², accelerometer only
NOISE = DATA / "noise_still.json"
IMU_TK = DATA / "real" / "xsens-multiposition" / "imu_tk"

WRITTEN = [f for f in mpcal.export_formats() if f["writes"]]


def input_sets(f):
    """The inputs to try for a format, in order: every calibration it can
    take (counts with a gyroscope, m/s² without) with the noise when it
    uses one."""
    cals = [None] if f["calibration"] == "unused" else [HALF1, MPS2]
    if f["calibration"] == "optional":
        cals.append(None)
    noises = [None] if f["noise"] == "unused" else [NOISE]
    if f["noise"] == "optional":
        noises.insert(0, None)
    return [(c, n) for c in cals for n in noises if c is not None or n is not None]


def cli_export(name, cal, noise, cwd):
    binary = os.environ.get("MPCAL_BINARY")
    if not binary:
        pytest.skip("MPCAL_BINARY (the mpcal command) not given")
    files = [str(p) for p in (cal, noise) if p is not None]
    done = subprocess.run([binary, "export", name, *files, "-o", "cli.out"], cwd=cwd,
                          capture_output=True, text=True, check=False)
    return done, cwd / "cli.out"


@pytest.mark.parametrize("f", WRITTEN, ids=[f["name"] for f in WRITTEN])
def test_every_format_byte_for_byte(f, tmp_path):
    written = 0
    for cal, noise in input_sets(f):
        done, cli_out = cli_export(f["name"], cal, noise, tmp_path)
        py_out = tmp_path / "py.out"
        if done.returncode != 0:
            # Refused by the command (raw counts for an autopilot, no
            # gyroscope): refused from Python alike, nothing written.
            with pytest.raises(mpcal.Error):
                mpcal.export(f["name"], cal, noise, path=py_out)
            assert not py_out.exists()
            continue
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            text = mpcal.export(f["name"], cal, noise, path=py_out)
        assert py_out.read_bytes() == cli_out.read_bytes()
        assert text == cli_out.read_text()
        # The same warnings as the command's, one finding each.
        said = [line for line in done.stderr.splitlines()
                if line.startswith("mpcal: warning: ")]
        found = [w.message for w in caught if issubclass(w.category, mpcal.MpcalWarning)]
        assert len(found) == len(said)
        for w in found:
            assert w.finding.kind in set(mpcal.FindingKind)
            assert w.finding.quantity and np.isfinite(w.finding.magnitude)
        # A calibration object loaded from the same file names it alike.
        if cal is not None:
            obj = mpcal.load_calibration(cal)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                assert mpcal.export(f["name"], obj, noise) == text
        written += 1
        os.remove(cli_out)
        os.remove(py_out)
    assert written > 0, f"no input that {f['name']} writes"


def test_kalibr_with_noise_of_arrays_and_options():
    # The noise as mpcal.noise returns it (a Section), named "<noise>".
    doc = json.loads(NOISE.read_text())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        text = mpcal.export("kalibr", noise=mpcal.Section(doc), rostopic="/imu/data")
        from_file = mpcal.export("kalibr", noise=NOISE, rostopic="/imu/data")
    assert 'rostopic: "/imu/data"' in text
    assert f"update_rate: {doc['rate_hz']:g}  # Hz" in text
    strip = lambda s: [l for l in s.splitlines() if not l.startswith("#")]
    assert strip(text) == strip(from_file)


def test_export_refusals(tmp_path):
    with pytest.raises(mpcal.Error, match="format 'openvins' needs a noise file") as e:
        mpcal.export("openvins", HALF1, path=tmp_path / "chain.yaml")
    assert e.value.kind == "input"
    assert not (tmp_path / "chain.yaml").exists()
    with pytest.raises(mpcal.Error, match="format='px5' is not a format") as e:
        mpcal.export("px5", HALF1)
    assert e.value.kind == "option"
    # The output may not replace an input.
    copy = tmp_path / "half1.json"
    copy.write_bytes(HALF1.read_bytes())
    with pytest.raises(mpcal.Error):
        mpcal.export("imu-tk-accel", copy, path=copy)
    assert copy.read_bytes() == HALF1.read_bytes()


def test_import_equals_the_commands(tmp_path):
    acc, gyro = IMU_TK / "xsens_acc.calib", IMU_TK / "xsens_gyro.calib"
    run_mpcal("import", "imu-tk", acc, gyro, "--units", "counts", "--gyro-units",
              "counts", "--gravity", 9.81744, "-o", "cli.json", cwd=tmp_path)
    cal = mpcal.import_calibration("imu-tk", acc, gyro, units="counts",
                                   gyro_units="counts", gravity=9.81744)
    cal.save(tmp_path / "py.json")
    cli = json.loads((tmp_path / "cli.json").read_text())
    py = json.loads((tmp_path / "py.json").read_text())
    assert cli.pop("provenance")["input"] == py.pop("provenance")["input"]
    assert py == cli   # every parameter the same doubles
    assert cal.std is None


def test_import_refusals():
    with pytest.raises(mpcal.Error, match="holds 20 numbers") as e:
        mpcal.import_calibration("imu-tk", DATA / "export" / "imu_tk_20_numbers.calib",
                                 units="counts")
    assert e.value.kind == "input"
    with pytest.raises(mpcal.Error, match="not a format mpcal reads"):
        mpcal.import_calibration("imu-tk-accel", IMU_TK / "xsens_acc.calib")
