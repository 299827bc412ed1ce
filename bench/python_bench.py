"""The Python module's two speed targets (bench/python_bench.sh).

  python_bench.py BUILD_DIR REPETITIONS

Each figure is the median of the runs; the Python and C++ runs alternate so
that a shared machine's load falls on both alike.
"""
import math
import statistics
import subprocess
import sys
import time

import numpy as np

import mpcal


def calibrate_ratio(build, reps):
    # The session of bench/speed_bench.sh: 1 kHz, 26 positions of 60 s, 88 s
    # of rest: 1.7 M rows (calibrate_floor.cc simulates the same). Two kinds
    # of arrays: the simulation's own (views of the rows the library holds,
    # as read_log's are) and copies of them (arrays of the caller's, float64
    # in C order: read in place). Both the wall-clock time and the CPU time
    # of the process (its threads' too), which a loaded machine does not
    # stretch as it does the clock.
    session = mpcal.simulate_static(seed=1, rate_hz=1000, dwell_s=60, initial_rest_s=88)
    t_copy, accel_copy = np.array(session.t), np.array(session.accel)
    wall = {"cpp": [], "own": [], "callers": []}
    cpu = {"cpp": [], "own": [], "callers": []}
    biases = set()

    def timed(t, accel, kind):
        for _ in range(2):  # the second of two: the first warms the caches
            start, start_cpu = time.perf_counter(), time.process_time()
            cal = mpcal.calibrate(t, accel)
            took, took_cpu = time.perf_counter() - start, time.process_time() - start_cpu
        wall[kind].append(took)
        cpu[kind].append(took_cpu)
        biases.add(float(cal.bias_mps2[0]))
        return cal

    # One run of each in turn, so that a shared machine's load falls on all
    # alike.
    # The C++ side's last of four calls in its process: its first ones are
    # slower (the allocator's heap grows and pages are first mapped; about
    # 0.096, 0.091, 0.079, 0.067 s of CPU here), which the Python process,
    # warm after the first repetition, no longer pays.
    for _ in range(reps):
        out = subprocess.run([f"{build}/bench/mpcal_calibrate_floor", "4"],
                             check=True, capture_output=True, text=True).stdout
        seconds, bias, cpu_s = out.split("\n")[3].split()
        wall["cpp"].append(float(seconds))
        cpu["cpp"].append(float(cpu_s))
        biases.add(float(bias))
        cal = timed(session.t, session.accel, "own")
        timed(t_copy, accel_copy, "callers")
    c, c_cpu = statistics.median(wall["cpp"]), statistics.median(cpu["cpp"])
    same = max(biases) - min(biases) <= 1e-9 * max(abs(b) for b in biases)
    print(f"calibrate, {len(session.t)} rows: CalibrateRecording in C++ {c:.3f} s "
          f"(CPU {c_cpu:.3f} s); same bias x on every path: {'yes' if same else 'NO'}")
    for kind, name in (("own", "the library's own arrays (read_log, simulate_static)"),
                       ("callers", "arrays of the caller's (read in place)")):
        w, p = statistics.median(wall[kind]), statistics.median(cpu[kind])
        ratio, ratio_cpu = w / c, p / c_cpu
        print(f"  mpcal.calibrate on {name}: {w:.3f} s, ratio {ratio:.3f}; CPU "
              f"{p:.3f} s, ratio {ratio_cpu:.3f} (target <= 1.10): "
              f"{'PASS' if max(ratio, ratio_cpu) <= 1.10 else 'FAIL'}")
    return cal


def affine_of(cal):
    """a = L y + o from the file's parameters (docs/method.md §2.1):
    L = T diag(1/(1+s)) k, o = -T diag(1/(1+s)) b."""
    yz, zx, zy = (cal.non_orthogonality_rad[k] for k in ("yz", "zx", "zy"))
    t = np.array([
        [1, 0, 0],
        [math.tan(yz), 1 / math.cos(yz), 0],
        [math.tan(zx) * math.tan(yz) - math.tan(zy) / math.cos(zx),
         math.tan(zx) / math.cos(yz), 1 / (math.cos(zx) * math.cos(zy))]])
    t_over_s = t @ np.diag(1 / (1 + cal.scale_factor_error))
    return t_over_s * cal.input.mps2_per_unit, -t_over_s @ cal.bias_mps2


def correct_ratio(cal, reps, rows=10_000_000):
    rng = np.random.default_rng(1)
    y = rng.normal(scale=9.8, size=(rows, 3))
    linear, offset = affine_of(cal)
    py, ref = [], []
    for _ in range(2):
        for _ in range(reps):
            start = time.perf_counter()
            expected = y @ linear.T + offset
            ref.append(time.perf_counter() - start)
        for _ in range(reps):
            start = time.perf_counter()
            corrected, _ = cal.correct(y)
            py.append(time.perf_counter() - start)
    ratio = statistics.median(py) / statistics.median(ref)
    agree = np.allclose(corrected, expected, rtol=1e-12, atol=1e-12)
    print(f"correct, {rows} rows: Calibration.correct {statistics.median(py):.3f} s, "
          f"numpy's y @ L.T + o {statistics.median(ref):.3f} s: ratio {ratio:.3f} "
          f"(target <= 1.50): {'PASS' if ratio <= 1.5 else 'FAIL'}; "
          f"same values: {'yes' if agree else 'NO'}")


def main():
    build, reps = sys.argv[1], int(sys.argv[2])
    cal = calibrate_ratio(build, reps)
    correct_ratio(cal, reps)


if __name__ == "__main__":
    main()
