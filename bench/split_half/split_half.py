#!/usr/bin/env python3
"""Split-half study of the real recordings: is mpcal's 1σ honest without truth?

Two halves of one session are two calibrations of the same sensor at the same
power-up (docs/method.md §9). Each recording is cut by time into two logs, each log
is calibrated by `mpcal calibrate`, and the two estimates are compared in
physical terms, since each half finds its own nominal unit factor for raw
counts: bias in the log's units b/k, gain per axis (1 + s)/k, angles as they
are, with k the half's `input.mps2_per_unit`. With honest 1σ and independent
halves z = (p1 - p2)/sqrt(σ1² + σ2²) is standard normal, so the RMS of z over
the parameters is about 1 (spread about ±0.24 for 9 values, ±0.29 for 6).
Then `mpcal repeat` on the two halves: nothing may be flagged at 1 %. The
gyroscope of an IMU session the same way, over the 9 entries of its matrix.

  split_half.py MPCAL_BINARY REAL_DATA_DIR [--workdir DIR]

Exit status 0 when every recording gives RMS z within the bar and repeat flags
nothing; 1 otherwise.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

RMS_Z_BAR = 1.25
NAMES = ['bias x', 'bias y', 'bias z', 'gain x', 'gain y', 'gain z',
         'theta yz', 'theta zx', 'theta zy']

# name, path under the data directory, rows in the first half (cut by time),
# calibrate options, number of parameters estimated. The Ferraris session of
# imucal (tests/data/real/imucal-ferraris) cannot be split: its six poses
# are each held once before the repeats of +x, +y, +z, so neither half by
# time nor by alternate positions has every axis up and down.
RECORDINGS = [
    ('xsens', 'xsens-multiposition/xsens_acc.mat', 25587,
     ['--units', 'counts', '--gravity', '9.81744'], 9),
]

# The gyroscope: name, accelerometer and gyroscope files (cut at the same
# row), rows in the first half, calibrate options. Each half finds its own
# nominal rad/s per count, and M is relative to it: the halves are compared
# as the effective matrix k M (rad/s per count), which is what the readings
# are multiplied by.
IMU_RECORDINGS = [
    ('xsens gyroscope', 'xsens-multiposition/xsens_acc.mat',
     'xsens-multiposition/xsens_gyro.mat', 25587,
     ['--units', 'counts', '--gyro-units', 'counts', '--gravity', '9.81744']),
]
GYRO_NAMES = ['m_xx', 'm_xy', 'm_xz', 'm_yx', 'm_yy', 'm_yz', 'm_zx', 'm_zy', 'm_zz']


def split(path, first_rows, directory):
    """Writes the first `first_rows` data rows and the rest; returns the paths.

    Without `first_rows`, the cut is at the middle row. A header line (a first
    line that is not numbers) is copied into both halves.
    """
    with open(path) as f:
        lines = f.readlines()
    header = []
    try:
        float(lines[0].replace(',', ' ').split()[0])
    except ValueError:
        header = [lines[0]]
        lines = lines[1:]
    cut = first_rows if first_rows is not None else len(lines) // 2
    stem, ext = os.path.splitext(os.path.basename(path))
    halves = []
    for i, part in enumerate((lines[:cut], lines[cut:])):
        out = os.path.join(directory, f'{stem}_half{i + 1}{ext}')
        with open(out, 'w') as f:
            f.writelines(header + part)
        halves.append(out)
    return halves


def physical(calibration):
    """Parameters and 1σ in the log's own units: b/k, (1 + s)/k, angles."""
    k = calibration['input']['mps2_per_unit']
    std = calibration['std']
    angles = calibration['non_orthogonality_rad']
    angles_std = std['non_orthogonality_rad']
    value = ([b / k for b in calibration['bias_mps2']] +
             [(1 + s) / k for s in calibration['scale_factor_error']] +
             [angles['yz'], angles['zx'], angles['zy']])
    sigma = ([b / k for b in std['bias_mps2']] +
             [s / k for s in std['scale_factor_error']] +
             [angles_std['yz'], angles_std['zx'], angles_std['zy']])
    return value, sigma


def study(mpcal, data_dir, name, relative, first_rows, options, parameters, directory):
    halves = split(os.path.join(data_dir, relative), first_rows, directory)
    calibrations = []
    for i, half in enumerate(halves):
        out = os.path.join(directory, f'{name}_half{i + 1}.json')
        subprocess.run([mpcal, 'calibrate', half, *options, '-o', out], check=True,
                       stdout=subprocess.DEVNULL)
        with open(out) as f:
            calibrations.append(json.load(f))
    (p1, s1), (p2, s2) = physical(calibrations[0]), physical(calibrations[1])
    z = [(p1[i] - p2[i]) / math.hypot(s1[i], s2[i]) for i in range(parameters)]
    rms = math.sqrt(sum(v * v for v in z) / len(z))
    repeat = subprocess.run(
        [mpcal, 'repeat', *[os.path.join(directory, f'{name}_half{i}.json') for i in (1, 2)]],
        stdout=subprocess.PIPE, text=True, check=True).stdout
    flagged = [line.split('  ')[0] for line in repeat.splitlines() if 'CHANGED' in line]
    print(f'{name}: {relative} cut after {first_rows or "the middle"} rows; '
          f'{options_text(options)}')
    for i, c in enumerate(calibrations):
        fit = c['fit']
        split_half = fit.get('split_half', {})
        print(f'  half {i + 1}: {fit["positions"]} positions, variance factor '
              f'{fit.get("variance_factor", float("nan")):.3g}, position scatter '
              f'{1e3 * fit.get("position_scatter_mps2", 0.0):.3g} mm/s2'
              + (f', own split-half RMS z {split_half["rms_z"]:.2f}'
                 if 'rms_z' in split_half else ''))
    print('  ' + '  '.join(f'{NAMES[i]} {z[i]:+.2f}' for i in range(parameters)))
    verdict = rms <= RMS_Z_BAR and not flagged
    print(f'  split-half RMS z {rms:.3f} over {parameters} parameters (bar: <= {RMS_Z_BAR}); '
          f'repeat flags at 1 %: {", ".join(flagged) if flagged else "none"}; '
          f'{"PASS" if verdict else "FAIL"}')
    return verdict


def gyro_study(mpcal, data_dir, name, accel, gyro, first_rows, options, directory):
    """The gyroscope's M from the two halves of an IMU session, z per entry."""
    accel_halves = split(os.path.join(data_dir, accel), first_rows, directory)
    gyro_halves = split(os.path.join(data_dir, gyro), first_rows, directory)
    fits = []
    for i in range(2):
        out = os.path.join(directory, f'{name.replace(" ", "_")}_half{i + 1}.json')
        subprocess.run([mpcal, 'calibrate', accel_halves[i], '--gyro-log', gyro_halves[i],
                        *options, '-o', out], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        with open(out) as f:
            fits.append(json.load(f)['gyroscope'])
    k = [g['input'].get('radps_per_unit', 1.0) for g in fits]
    z = [(k[0] * fits[0]['m'][i] - k[1] * fits[1]['m'][i]) /
         math.hypot(k[0] * fits[0]['std']['m'][i], k[1] * fits[1]['std']['m'][i])
         for i in range(9)]
    rms = math.sqrt(sum(v * v for v in z) / len(z))
    repeat = subprocess.run(
        [mpcal, 'repeat', *[os.path.join(directory, f'{name.replace(" ", "_")}_half{i}.json')
                            for i in (1, 2)]],
        stdout=subprocess.PIPE, text=True, check=True).stdout
    gyro_part = repeat[repeat.find('gyroscope over'):]
    flagged = [line.split('  ')[0] for line in gyro_part.splitlines() if 'changed (p' in line]
    print(f'{name}: {accel} + {gyro} cut after {first_rows} rows; {options_text(options)}')
    for i, g in enumerate(fits):
        fit = g['fit']
        print(f'  half {i + 1}: {fit["turns"]} turns, variance factor {fit["variance_factor"]:.3g}, '
              f'turn residual {math.degrees(fit["residual_rms_after_rad"]):.3f} deg, '
              f'nominal {k[i]:.6g} rad/s per count')
    print('  ' + '  '.join(f'{GYRO_NAMES[i]} {z[i]:+.2f}' for i in range(9)))
    verdict = rms <= RMS_Z_BAR and not flagged
    print(f'  split-half RMS z {rms:.3f} over 9 entries of k M (bar: <= {RMS_Z_BAR}); '
          f'repeat flags at 1 %: {", ".join(flagged) if flagged else "none"}; '
          f'{"PASS" if verdict else "FAIL"}')
    return verdict


def options_text(options):
    return ' '.join(options)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('mpcal')
    parser.add_argument('data_dir')
    parser.add_argument('--workdir')
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        directory = args.workdir or scratch
        os.makedirs(directory, exist_ok=True)
        results = [study(args.mpcal, args.data_dir, *recording, directory)
                   for recording in RECORDINGS]
        results += [gyro_study(args.mpcal, args.data_dir, *recording, directory)
                    for recording in IMU_RECORDINGS]
    print('PASS' if all(results) else 'FAIL')
    return 0 if all(results) else 1


if __name__ == '__main__':
    sys.exit(main())
