#!/usr/bin/env python3
"""The noise values of every filter file, read back with a YAML parser
(python3-yaml, not mpcal's reader):

  - a value the record did not measure says so on its own comment line
    before its key, and only such a value (the command's warnings name the
    same keys);
  - a bound never wins over a measured value by the "largest axis" rule: a
    noise file whose measured axis is 100 times below the others' bounds
    gives the measured value in every file that takes one value per sensor;
  - --strict refuses every file that would hold an unmeasured value (exit 1,
    one line, no file), and writes the ones that would not;
  - --inflate X multiplies exactly the noise values by X (ROS: the
    variances by X^2), says so in the file and gives the record's values
    beside them; X below 1 is refused.

usage: filter_noise_values_test.py MPCAL_BINARY PROJECT_ROOT WORK_DIR
"""
import copy
import json
import pathlib
import re
import subprocess
import sys

import yaml

# Format, the calibration it needs, and the noise keys it writes: (path in
# the YAML, how the value scales with the inflation factor).
FORMATS = {
    'kalibr': (False, {k: 1 for k in ('accelerometer_noise_density', 'accelerometer_random_walk',
                                      'gyroscope_noise_density', 'gyroscope_random_walk')}),
    'kalibr-scale-misalignment': (True, {'imu0.' + k: 1 for k in (
        'accelerometer_noise_density', 'accelerometer_random_walk',
        'gyroscope_noise_density', 'gyroscope_random_walk')}),
    'openvins': (True, {'imu0.' + k: 1 for k in (
        'accelerometer_noise_density', 'accelerometer_random_walk',
        'gyroscope_noise_density', 'gyroscope_random_walk')}),
    'orb-slam3': (False, {k: 1 for k in ('IMU.NoiseGyro', 'IMU.NoiseAcc', 'IMU.GyroWalk', 'IMU.AccWalk')}),
    'vins': (False, {k: 1 for k in ('acc_n', 'gyr_n', 'acc_w', 'gyr_w')}),
    'kf-gins': (False, {'imunoise.' + k: 1 for k in ('arw', 'vrw', 'gbstd', 'abstd')}),
    'ros-imu': (False, {k: 2 for k in ('angular_velocity_covariance', 'linear_acceleration_covariance')}),
}
# Keys that are not noise values of the record and never inflated.
FIXED = {'kf-gins': ('imunoise.corrtime', 'imunoise.gsstd', 'imunoise.asstd'),
         'orb-slam3': ('IMU.Frequency',), 'kalibr': ('update_rate',),
         'ros-imu': ('orientation_covariance',)}


def load(path):
    text = path.read_text()
    # OpenCV's files begin with a YAML 1.0 directive that PyYAML refuses.
    return yaml.safe_load(re.sub(r'^%YAML:1\.0\n', '', text)), text


def get(doc, key):
    for part in key.split('.') if not key.startswith('IMU.') else [key]:
        doc = doc[part]
    return doc


def run(mpcal, *args, cwd):
    return subprocess.run([mpcal, *args], capture_output=True, text=True, cwd=cwd)


def export(mpcal, work, fmt, noise, calib, out, *extra):
    files = [str(noise)] + ([str(calib)] if FORMATS[fmt][0] else [])
    return run(mpcal, 'export', fmt, *files, '-o', out, *extra, cwd=work)


def warned_keys(stderr):
    return set(re.findall(r'mpcal: warning: \S+: (\S+) was not measured', stderr))


def test_bound_on_its_own_line(mpcal, data, work):
    """Each key warned as not measured has a comment line of its own saying
    NOT MEASURED before its key; no other key has one."""
    for fmt in FORMATS:
        r = export(mpcal, work, fmt, data / 'noise_still.json', data / 'xsens_imu_half1.json', fmt + '.yaml')
        assert r.returncode == 0, (fmt, r.stderr)
        warned = warned_keys(r.stderr)
        text = (work / (fmt + '.yaml')).read_text()
        lines = text.splitlines()
        marked = set()
        for i, line in enumerate(lines):
            m = re.match(r'\s*# (\S+) .*NOT MEASURED', line)
            if not m:
                continue
            marked.add(m.group(1))
            # The key itself comes after it (Kalibr's file: after the
            # comment lines of all four).
            # (ORB-SLAM3 writes the whole dotted key, Kalibr's chain its last part.)
            key = '(%s|%s)' % (re.escape(m.group(1)), re.escape(m.group(1).split('.')[-1]))
            assert any(re.match(r'\s*%s:' % key, ln) for ln in lines[i + 1:]), (fmt, line)
        if fmt != 'ros-imu':  # the test file's random walks are not measured
            assert warned, (fmt, r.stderr)
        assert warned == marked, (fmt, warned, marked)


def test_bound_never_wins(mpcal, data, work):
    """The accelerometer's random walk measured on x only, 100 times below
    the bounds of y and z: the one-value files hold the measured x."""
    doc = json.loads((data / 'noise_still.json').read_text())
    axes = doc['accelerometer']['axes']
    key = 'random_walk_mps3_per_rthz'
    axes['x'][key] = {'status': 'measured', 'value': 1e-5, 'lo': 8e-6, 'hi': 1.2e-5, 'tau_range_s': [20.0, 45.0]}
    for a in 'yz':
        axes[a][key] = {'status': 'not_seen', 'upper_bound': 1e-3, 'record_needed_s': 600.0}
    noise = work / 'noise_x_measured.json'
    noise.write_text(json.dumps(doc))
    rate = doc['rate_hz']
    expect = {'kalibr': ('accelerometer_random_walk', 1e-5), 'orb-slam3': ('IMU.AccWalk', 1e-5),
              'vins': ('acc_w', 1e-5 * rate ** 0.5), 'openvins': ('imu0.accelerometer_random_walk', 1e-5)}
    for fmt, (k, v) in expect.items():
        r = export(mpcal, work, fmt, noise, data / 'xsens_imu_half1.json', 'one.yaml')
        assert r.returncode == 0, (fmt, r.stderr)
        # (PyYAML reads YAML 1.1: an exponent without a dot is a string.)
        got = float(get(load(work / "one.yaml")[0], k))
        assert abs(got / v - 1) < 1e-5, (fmt, got, v)
        assert k.split('.')[-1] not in warned_keys(r.stderr), (fmt, r.stderr)
    # The Kalibr file says which axes were not measured and that their
    # bounds were not used.
    assert export(mpcal, work, 'kalibr', noise, None, 'k.yaml').returncode == 0
    text = (work / 'k.yaml').read_text()
    assert 'not measured on y, z (its bound not used)' in text, text


def test_strict(mpcal, data, work):
    """--strict: every format that would hold a bound (the test file's random
    walks) is refused with one line and no file; with the random walks
    measured on every axis, the files are written (kf-gins still wants B)."""
    for fmt in FORMATS:
        if fmt == 'ros-imu':  # white noise only, measured on every axis
            continue
        out = work / ('strict_' + fmt + '.yaml')
        r = export(mpcal, work, fmt, data / 'noise_still.json', data / 'xsens_imu_half1.json', out.name, '--strict')
        assert r.returncode == 1, (fmt, r.returncode, r.stderr)
        assert r.stderr.startswith('mpcal: error: ') and r.stderr.count('\n') == 1, (fmt, r.stderr)
        assert '--strict' in r.stderr and 'not measured' in r.stderr, (fmt, r.stderr)
        assert not out.exists(), fmt
    doc = json.loads((data / 'noise_still.json').read_text())
    for sensor, key in (('accelerometer', 'random_walk_mps3_per_rthz'), ('gyroscope', 'random_walk_radps2_per_rthz')):
        for a in 'xyz':
            doc[sensor]['axes'][a][key] = {'status': 'measured', 'value': 2e-5, 'lo': 1e-5, 'hi': 3e-5,
                                           'tau_range_s': [20.0, 45.0]}
    noise = work / 'noise_all_measured.json'
    noise.write_text(json.dumps(doc))
    for fmt in FORMATS:
        r = export(mpcal, work, fmt, noise, data / 'xsens_imu_half1.json', 'strict_ok.yaml', '--strict')
        if fmt == 'kf-gins':  # gbstd: B not measured on five of the six axes
            assert r.returncode == 1 and 'gbstd' in r.stderr, (fmt, r.stderr)
        else:
            assert r.returncode == 0, (fmt, r.stderr)
    r = run(mpcal, 'export', 'kalibr', str(data / 'xsens_imu_half1.json'), '-o', 'x.yaml', '--strict', cwd=work)
    assert r.returncode != 0 and r.stderr.startswith('mpcal: error: '), r.stderr


def test_inflate(mpcal, data, work):
    """--inflate 3: the noise values 3 times the record's (variances 9),
    every other value unchanged, the factor and the record's values in the
    file's comments."""
    for fmt, (_, keys) in FORMATS.items():
        plain = export(mpcal, work, fmt, data / 'noise_still.json', data / 'xsens_imu_half1.json', 'p.yaml')
        inflated = export(mpcal, work, fmt, data / 'noise_still.json', data / 'xsens_imu_half1.json', 'i.yaml',
                          '--inflate', '3')
        assert plain.returncode == 0 and inflated.returncode == 0, (fmt, plain.stderr, inflated.stderr)
        p, _ = load(work / 'p.yaml')
        i, text = load(work / 'i.yaml')
        assert "INFLATED x3 at the user's request" in text, (fmt, text)
        assert 'not inflated' not in text, fmt
        for key, power in keys.items():
            pv, iv = get(p, key), get(i, key)
            pv, iv = (pv, iv) if isinstance(pv, list) else ([pv], [iv])
            diagonal = pv[0::4] if len(pv) == 9 else pv  # ROS: the comment gives the diagonal
            for a, b in zip(pv, iv):
                assert b == 0 or abs(b / a / 3 ** power - 1) < 2e-5, (fmt, key, a, b)
            # The record's value, beside the inflated one.
            line = next(ln for ln in text.splitlines()
                        if re.match(r'\s*%s:' % re.escape(key.split('.')[-1] if not key.startswith('IMU.') else key), ln))
            assert 'INFLATED x3' in line, (fmt, line)
            shown = [float(x) for x in re.findall(r'[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?',
                                                  line.split("the record's")[1])]
            assert len(shown) == len(diagonal), (fmt, line)
            for a, b in zip(diagonal, shown):
                assert abs(b / a - 1) < 1e-4 if a else b == 0, (fmt, key, pv, shown)
        for key in FIXED.get(fmt, ()):
            assert get(p, key) == get(i, key), (fmt, key)
    for bad in ('0.5', 'nan'):
        r = export(mpcal, work, 'kalibr', data / 'noise_still.json', None, 'bad.yaml', '--inflate', bad)
        assert r.returncode != 0 and not (work / 'bad.yaml').exists(), (bad, r.stderr)
        assert r.stderr.startswith('mpcal: error: ') and '--inflate' in r.stderr, (bad, r.stderr)


def test_noise_kalibr_inflate(mpcal, data, work):
    """noise --kalibr --inflate 2 on a still record: the four values twice the
    uninflated file's, the factor in the header, the record's values beside."""
    still = data / 'noise_still.csv'
    r1 = run(mpcal, 'noise', str(still), '--kalibr', 'a.yaml', cwd=work)
    r2 = run(mpcal, 'noise', str(still), '--kalibr', 'b.yaml', '--inflate', '2', cwd=work)
    assert r1.returncode == 0 and r2.returncode == 0, (r1.stderr, r2.stderr)
    a, _ = load(work / 'a.yaml')
    b, text = load(work / 'b.yaml')
    for key in FORMATS['kalibr'][1]:
        assert abs(b[key] / a[key] / 2 - 1) < 2e-6, (key, a[key], b[key])
        line = next(ln for ln in text.splitlines() if ln.startswith(key + ':'))
        assert re.search(r"INFLATED x2: the record's (measured value|upper bound) %s" % re.escape('%.6e' % a[key]),
                         line), line
    assert a['update_rate'] == b['update_rate']
    assert 'INFLATED x2' in r2.stdout, r2.stdout
    r = run(mpcal, 'noise', str(still), '--json', 'n.json', '--inflate', '2', cwd=work)
    assert r.returncode != 0 and '--kalibr' in r.stderr, r.stderr


def main():
    mpcal, root, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    data = root / 'tests' / 'data'
    tests = [v for k, v in globals().items() if k.startswith('test_')]
    for test in tests:
        test(mpcal, data, work)
        print('ok  %s' % test.__name__)
    print('%d tests passed' % len(tests))
    return 0


if __name__ == '__main__':
    sys.exit(main())
