#!/usr/bin/env python3
"""Compares two calibration files parameter by parameter: each parameter of
TEST must lie within K times the 1σ of REFERENCE (the file's own `std`) of
REFERENCE's value, and with RMS_GYRO, the RMS of the gyroscope's
|difference| / σ over its parameters within RMS_GYRO (two files within 1σ
of each other in the sense of the validation study: differences whose
spread is at most their 1σ). Prints one line per parameter (|difference| /
σ) and exits 1 if any lies beyond.

  within_sigma.py REFERENCE.json TEST.json [K [K_GYRO [RMS_GYRO]]]
      (K = 1, K_GYRO = K, RMS_GYRO: not checked)

Accelerometer: bias_mps2, scale_factor_error, non_orthogonality_rad;
gyroscope (when both have it): m, bias_radps. Read with the json module
only, not through mpcal.
"""
import json
import sys


def pairs(ref, test, std, path):
    if isinstance(ref, dict):
        for k in ref:
            yield from pairs(ref[k], test[k], std[k], path + "." + k)
    elif isinstance(ref, list):
        for i, (r, t, s) in enumerate(zip(ref, test, std)):
            yield path + "[%d]" % i, r, t, s
    else:
        yield path, ref, test, std


def main():
    ref = json.load(open(sys.argv[1]))
    test = json.load(open(sys.argv[2]))
    k = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    k_gyro = float(sys.argv[4]) if len(sys.argv) > 4 else k
    rms_gyro = float(sys.argv[5]) if len(sys.argv) > 5 else None
    fields = [(ref, test, ref["std"], n, k, False)
              for n in ("bias_mps2", "scale_factor_error", "non_orthogonality_rad")]
    if "gyroscope" in ref and "gyroscope" in test:
        g, h = ref["gyroscope"], test["gyroscope"]
        fields += [(g, h, g["std"], n, k_gyro, True) for n in ("m", "bias_radps")]
    beyond = 0
    gyro_z = []
    for r, t, s, name, limit, gyro in fields:
        for path, a, b, sigma in pairs(r[name], t[name], s[name], name):
            z = abs(b - a) / sigma
            beyond += z > limit
            if gyro:
                gyro_z.append(z)
            print("%-28s %14.8g %14.8g  %.3f sigma" % (path, a, b, z))
    print("%d parameters beyond the limit (%g sigma; gyroscope %g sigma)" % (beyond, k, k_gyro))
    if rms_gyro is not None:
        if not gyro_z:
            print("no gyroscope in both files to take the RMS of")
            return 1
        rms = (sum(z * z for z in gyro_z) / len(gyro_z)) ** 0.5
        print("gyroscope: RMS %.3f sigma over %d parameters (limit %g)"
              % (rms, len(gyro_z), rms_gyro))
        beyond += rms > rms_gyro
    return 0 if beyond == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
