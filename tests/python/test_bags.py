"""read_log on a recording with a topic per sensor gives the rows and the
calibration `mpcal calibrate --accel-topic --gyro-topic` gives."""
import json
import warnings

import numpy as np
import pytest

import mpcal
from conftest import DATA, run_mpcal

BAG = DATA / "streams" / "two_rate.bag"   # accelerometer 50 Hz, gyroscope 100 Hz
ACCEL, GYRO = "/camera/accel/sample", "/camera/gyro/sample"
RTOL = 1e-9   # the same library code on the same doubles


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    d = tmp_path_factory.mktemp("two_topics")
    run_mpcal("calibrate", BAG, "--accel-topic", ACCEL, "--gyro-topic", GYRO, "-o",
              "two.json", cwd=d)
    return json.loads((d / "two.json").read_text())


@pytest.mark.parametrize("time", ["header", "receive"])
def test_two_topics_equal_the_commands(cli, time):
    # The fixture's messages were received at their header stamps: both
    # clocks give the command's numbers.
    rec = mpcal.read_log(BAG, accel_topic=ACCEL, gyro_topic=GYRO, time=time)
    # 4050 accelerometer messages, one outside the gyroscope's span dropped.
    assert len(rec) == 4049
    assert rec.gyro is not None and rec.gyro.shape == (4049, 3)
    # The accelerometer's rows are its messages as they are.
    accel_only = mpcal.read_log(BAG, topic=ACCEL, time=time)
    first = int(np.searchsorted(accel_only.t, rec.t[0]))
    np.testing.assert_array_equal(rec.t, accel_only.t[first:first + len(rec)])
    np.testing.assert_array_equal(rec.accel, accel_only.accel[first:first + len(rec)])
    cal = mpcal.calibrate(rec.t, rec.accel, rec.gyro)
    np.testing.assert_allclose(cal.bias_mps2, cli["bias_mps2"], rtol=RTOL)
    np.testing.assert_allclose(cal.std.bias_mps2, cli["std"]["bias_mps2"], rtol=RTOL)
    np.testing.assert_allclose(cal.scale_factor_error, cli["scale_factor_error"],
                               rtol=RTOL)
    g = cal.gyroscope
    np.testing.assert_allclose(g.m, cli["gyroscope"]["m"], rtol=RTOL, atol=1e-15)
    np.testing.assert_allclose(g.bias_radps, cli["gyroscope"]["bias_radps"], rtol=RTOL,
                               atol=1e-15)


def test_gyro_topic_of_the_imu_topics_only():
    # The accelerometer's messages carry zero rates; the gyroscope's own
    # stream replaces them.
    rec = mpcal.read_log(BAG, accel_topic=ACCEL, gyro_topic=GYRO)
    assert np.abs(rec.gyro).max() > 0.1
    with pytest.raises(mpcal.Error, match="topic '/chatter' is of type std_msgs/String"):
        mpcal.read_log(BAG, accel_topic=ACCEL, gyro_topic="/chatter")


def test_topic_and_accel_topic_are_exclusive():
    with pytest.raises(mpcal.Error, match="not both") as e:
        mpcal.read_log(BAG, topic="/imu/data", accel_topic=ACCEL, gyro_topic=GYRO)
    assert e.value.kind == "option"
    assert set(e.value.advice) == {"topic", "accel_topic"}


def test_three_imu_topics_need_choosing():
    with pytest.raises(mpcal.Error, match="3 sensor_msgs/Imu topics") as e:
        mpcal.read_log(BAG, gyro_topic=GYRO)
    # The advice names read_log's keywords, never the command's flags.
    assert all(not k.startswith("-") for k in e.value.advice)
