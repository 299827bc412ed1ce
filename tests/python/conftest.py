"""What the Python module's tests share: the data folder, the command to
compare with, and the Xsens recording (imu_tk's, tests/data/real/)."""
import os
import pathlib
import subprocess

import pytest

DATA = pathlib.Path(os.environ.get(
    "MPCAL_TEST_DATA", pathlib.Path(__file__).resolve().parents[1] / "data"))
XSENS = DATA / "real" / "xsens-multiposition"
XSENS_ACC = XSENS / "xsens_acc.mat"
XSENS_GYRO = XSENS / "xsens_gyro.mat"
XSENS_GRAVITY_MPS2 = 9.81744  # the site's gravity, as its README gives it


def run_mpcal(*args, cwd):
    binary = os.environ.get("MPCAL_BINARY")
    if not binary:
        pytest.skip("MPCAL_BINARY (the mpcal command) not given")
    done = subprocess.run([binary, *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, check=False)
    assert done.returncode == 0, done.stderr
    return done
