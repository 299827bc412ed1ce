"""mpcal: field calibration of MEMS accelerometers (multi-position method)
and gyroscopes (from the turns between the positions), on numpy arrays.

    >>> import mpcal
    >>> rec = mpcal.read_log("xsens_acc.mat", units="counts")
    >>> cal = mpcal.calibrate(rec.t, rec.accel, units="counts", gravity=9.81744)
    >>> cal.bias_mps2, cal.std.bias_mps2
    >>> a_mps2, _ = cal.correct(rec.accel)

Units are in the names: ``t`` in seconds, accelerometer readings in the
units given (``"mps2"``, ``"g"`` or raw ``"counts"``), gyroscope readings in
rad/s (``"rads"``), deg/s (``"dps"``) or ``"counts"``. Arrays are N×3
(x, y, z per row) of any real dtype; the arrays :func:`read_log` and
:func:`simulate_static` return are the library's own rows, taken as they
are; other arrays of float64 in C order are read in place, without a copy,
and the rest converted first.

Bad input raises :class:`mpcal.Error` (a ValueError) with ``kind``,
``advice`` (the keyword arguments the message speaks of) and ``figures``;
findings that do not stop the work are :class:`Finding` objects (a
:class:`FindingKind`, the figures in SI units, the keyword arguments that
would change them) in the results' ``findings``, and are issued as
:class:`MpcalWarning` with the finding attached. :func:`export` writes
other tools' files (Kalibr, OpenVINS, imu_tk, ...) as ``mpcal export``
does; :func:`import_calibration` reads theirs.
"""

import json
import math
import os
from collections.abc import Mapping
import warnings as _warnings

import numpy as np

from . import _mpcal
from ._errors import Error, Finding, FindingKind, MpcalWarning

__all__ = ["Error", "Finding", "FindingKind", "MpcalWarning", "Recording", "Calibration",
           "Section", "read_log", "detect", "calibrate", "noise", "load_calibration",
           "simulate_static", "simulate_noise", "Simulation", "export",
           "import_calibration", "export_formats", "__version__"]

__version__ = _mpcal.__version__

#: A log in memory, as :func:`read_log` returns it. Attributes: ``t`` (N,
#: seconds in the log's own clock, strictly increasing), ``accel`` (N×3, in
#: ``units``: "mps2", "g" or "counts"), ``gyro`` (N×3 in rad/s, or raw
#: counts when ``gyro_units`` is "counts"; None without a gyroscope),
#: ``source`` and ``warnings`` (the reader's findings). The arrays are
#: read-only views of the rows the reader holds: no copy.
Recording = _mpcal.Recording

_READ_LOG_DEFAULTS = _mpcal._read_log_defaults()
_CALIBRATE_DEFAULTS = _mpcal._calibrate_defaults()


def _findings(found):
    """Findings as the library hands them over (dicts, or a reader's
    sentences) as :class:`Finding` objects."""
    return [f if isinstance(f, Finding) else
            Finding(**f) if isinstance(f, dict) else Finding("log", f) for f in found]


def _warn(findings, stacklevel=3):
    for finding in findings:
        _warnings.warn(MpcalWarning(finding), stacklevel=stacklevel)


def _options(function, given, defaults):
    unknown = sorted(set(given) - set(defaults))
    if unknown:
        raise TypeError(f"{function}() got unknown keyword argument(s) "
                        f"{', '.join(unknown)}; known: {', '.join(sorted(defaults))}")
    merged = dict(defaults)
    merged.update(given)
    return merged


def _shaped(name, values, columns):
    """`values` as float64 in C order, (N,) or (N, 3) (a view when they are
    already, else a converted copy); else an mpcal.Error naming the
    argument. The values are not looked at: see _rows and _reading."""
    a = np.asarray(values)
    if a.dtype.kind not in "fiu":
        raise Error(f"{name}: dtype {a.dtype} is not a real number type; give "
                    f"float64 (or any integer or float dtype)", kind="input")
    if columns == 1 and a.ndim != 1:
        raise Error(f"{name}: shape {a.shape}, expected (N,): one time (s) per sample",
                    kind="input")
    if columns == 3 and (a.ndim != 2 or a.shape[1] != 3):
        raise Error(f"{name}: shape {a.shape}, expected (N, 3): one row per sample, "
                    f"columns x, y, z", kind="input")
    return np.ascontiguousarray(a, dtype=np.float64)


def _not_finite(name, a):
    """The error for an array with a NaN or an infinity: its first such row
    and how many there are."""
    finite = np.isfinite(a)
    bad = np.flatnonzero(~finite.reshape(len(a), -1).all(axis=1))
    return Error(f"{name}: row {bad[0]} is not finite ({a[bad[0]]}), and "
                 f"{len(bad)} row(s) in all; drop or fill them first", kind="input",
                 figures={"argument": name, "row": int(bad[0]), "rows": len(bad)})


def _rows(name, values, columns):
    """`values` as float64 in C order, (N,) or (N, 3), all finite; else an
    mpcal.Error naming the argument (for correct, whose arithmetic would
    carry a NaN into its output)."""
    a = _shaped(name, values, columns)
    if not np.isfinite(a).all():
        raise _not_finite(name, a)
    return a


def _reading(call, arrays, *args):
    """`call(*args)`, which reads `arrays` ({argument: array or None}) in
    place. The library refuses a NaN or an infinity where it first reads the
    rows, naming the column and the row; that becomes the error naming the
    argument (no pass over the arrays here when they are finite)."""
    try:
        return call(*args)
    except Error as e:
        name = e.figures.get("argument")
        if arrays.get(name) is None:
            raise
        raise _not_finite(name, arrays[name]) from None


def _same_memory(a, b):
    return (isinstance(a, np.ndarray) and a.shape == b.shape and a.strides == b.strides
            and a.__array_interface__["data"][0] == b.__array_interface__["data"][0])


def _recording_of(t, accel, gyro, units, gyro_units):
    """The Recording whose own arrays these are (read_log's, a simulation's),
    with the units given, so that the library takes its rows as they are;
    else None (the arrays are copied)."""
    recording = getattr(accel, "base", None)
    if not isinstance(recording, Recording) or units != recording.units:
        return None
    if not (_same_memory(accel, recording.accel) and _same_memory(t, recording.t)):
        return None
    if gyro is None:
        return recording if recording.gyro is None else None
    if recording.gyro is None or gyro_units != recording.gyro_units:
        return None
    return recording if _same_memory(gyro, recording.gyro) else None


def _same_length(**arrays):
    lengths = {k: len(v) for k, v in arrays.items() if v is not None}
    if len(set(lengths.values())) > 1:
        shown = ", ".join(f"{k} has {n}" for k, n in lengths.items())
        raise Error(f"the arrays differ in length ({shown} rows): give one row per "
                    f"sample in each", kind="input")


def read_log(path, **options):
    """Read a log (delimited text as loggers write it, a ROS 1 bag, an MCAP
    file or a ROS 2 bag directory) into a :data:`Recording`.

    Keyword arguments (the log's layout, as ``mpcal calibrate`` reads it):

    columns : str
        "t=NAME|INDEX,ax=...,ay=...,az=...[,gx=...,gy=...,gz=...]", 0-based
        indices; default: from the header, else t, ax, ay, az in order.
    units : str
        Units of the accelerometer columns: "mps2" (default), "g", "counts".
    gyro_units : str
        Units of the gyroscope columns: "rads" (default), "dps" (converted
        to rad/s on reading) or "counts" (kept).
    time_unit : str
        "auto" (default), "s", "ms", "us", "ns" or "index".
    rate_hz : float
        Sample rate (Hz) when the time column is a sample index or absent.
    topic : str
        The sensor_msgs/Imu topic of a bag or MCAP file (default: its only
        one).
    accel_topic, gyro_topic : str
        A recording that publishes the sensors apart (a topic each, at their
        own rates and stamps): the accelerometer's topic gives the rows, the
        gyroscope's (in this recording, or in ``gyro_log``'s) is averaged
        onto them, as ``mpcal calibrate`` does with two topics.
    time : str
        A bag's time: "header" (default: each message's header stamp) or
        "receive" (when the recorder received it).
    gyro_log, gyro_columns : str
        The gyroscope in a file of its own, row by row with the log
        (imu_tk's xsens_gyro.mat), and its column mapping.

    The reader's findings (gaps, duplicated times, two streams that do not
    line up) are in ``warnings`` (sentences) and issued as
    :class:`MpcalWarning` (kind "log"). Raises :class:`Error` for a missing or
    malformed file (naming the line and column), or invalid options.
    """
    recording = _mpcal._read_log(str(path), _options("read_log", options,
                                                     _READ_LOG_DEFAULTS))
    _warn(recording.warnings)
    return recording


def _arrays_provenance(units, gravity, options):
    given = {k: v for k, v in options.items() if v != _CALIBRATE_DEFAULTS[k]}
    args = [f"units={units!r}"]
    if gravity is not None:
        args.append(f"gravity={gravity!r}")
    args += [f"{k}={v!r}" for k, v in sorted(given.items())]
    return "mpcal.calibrate(t, accel, " + ", ".join(args) + ")"


def calibrate(t, accel, gyro=None, units="mps2", gravity=None, gyro_units="rads",
              **options):
    """Calibrate an accelerometer (and the gyroscope with it) from a
    multi-position session: detect the static positions, estimate bias,
    scale-factor errors and non-orthogonality with their 1σ, and, when
    ``gyro`` is given, the gyroscope's matrix M and bias from the turns.

    t : array (N,)
        Time of each sample (s), strictly increasing.
    accel : array (N, 3)
        Accelerometer readings in ``units``: "mps2", "g" or "counts" (raw
        ADC counts: the nominal scale is found from the positions).
    gyro : array (N, 3), optional
        Gyroscope readings of the same samples in ``gyro_units``: "rads",
        "dps" or "counts".
    gravity : float, optional
        Local magnitude of gravity (m/s²); default 9.80665, or the WGS84
        normal gravity at ``latitude_deg`` (deg) and ``height_m`` (m).

    Options (the library's defaults in parentheses; as ``mpcal calibrate``'s
    flags): ``window_s`` (1.0 s), ``min_static_s`` (2.0 s), ``settle_s``
    (0.3 s), ``threshold`` (3.0 × the quiet level), ``max_still_g`` (0.05
    g), ``merge_gap_s`` (1.0 s), ``merge_angle_deg`` (3.0 deg),
    ``range_g`` (0: found from the data), ``model`` ("shin-el-sheimy-9" or
    "bias-scale-6"), ``robust`` ("none", "huber", "cauchy"),
    ``counts_per_g`` (raw counts: the datasheet's sensitivity; 0: the
    fitted sphere), ``gyro_window_s`` (1.0 s), ``gyro_g_sensitivity``
    ("auto", "on", "off"), ``calibrate_gyroscope`` (True).

    Arrays of float64 in C order (what numpy makes by default) are read
    where they are, without a copy (a NaN or an infinity is refused, naming
    the argument and the row, as the library first reads them); others are
    converted first (as ``numpy.ascontiguousarray(a, dtype=float64)``), and
    a gyroscope in "dps" is converted to rad/s. The call reads them while
    it runs, without the GIL: change them from no other thread meanwhile.

    Returns a :class:`Calibration` whose attributes mirror the calibration
    file ``mpcal calibrate -o`` writes, and ``findings``: each warning as a
    :class:`Finding` (kind, figures, the keyword arguments that would change
    it), also issued as :class:`MpcalWarning`. Raises :class:`Error` when the session cannot be
    calibrated (kind "session", with the advice), the readings do not fit
    ``units`` (kind "units"), the fit does not converge, or an argument is
    malformed (naming it).
    """
    options = _options("calibrate", options, _CALIBRATE_DEFAULTS)
    if gravity is not None and not math.isfinite(float(gravity)):
        raise Error(f"gravity: {gravity} is not a number of m/s²", kind="option",
                    advice={"gravity": None})
    provenance = _arrays_provenance(units, gravity, options)
    recording = _recording_of(t, accel, gyro, units, gyro_units)
    if recording is not None:
        native = _mpcal._calibrate_recording(recording, gravity, options, provenance)
        result = Calibration(*native)
        _warn(result.findings)
        return result
    # The library reads the arrays in place.
    arrays = {"t": _shaped("t", t, 1), "accel": _shaped("accel", accel, 3),
              "gyro": None if gyro is None else _shaped("gyro", gyro, 3)}
    _same_length(**arrays)
    native = _reading(_mpcal._calibrate, arrays, arrays["t"], arrays["accel"],
                      arrays["gyro"], units, gyro_units, gravity, options, provenance)
    result = Calibration(*native)
    _warn(result.findings)
    return result


_DETECT_KEYS = ("window_s", "min_static_s", "settle_s", "threshold", "max_still_g",
                "merge_gap_s", "merge_angle_deg", "range_g")


def detect(t, accel, units="mps2", gravity=None, **options):
    """Find the static positions of a session and judge how well they cover
    the sphere for a calibration, as ``mpcal detect`` does.

    t : array (N,), seconds; accel : array (N, 3) in ``units`` ("mps2",
    "g", "counts"); gravity : float (m/s², default 9.80665), to check the
    units by. Options as :func:`calibrate`'s static detection:
    ``window_s``, ``min_static_s``, ``settle_s``, ``threshold``,
    ``max_still_g``, ``merge_gap_s``, ``merge_angle_deg``, ``range_g``.

    Returns a :class:`Section` with what ``mpcal detect --json`` writes
    (format mpcal.detection/1): ``intervals`` (one per static position:
    ``begin``, ``end`` (row indices, end excluded), ``start_s``, ``end_s``,
    ``duration_s`` (s, the log's clock), ``samples``, ``mean``, ``std`` and
    ``noise`` (in ``units``), ``direction`` (unit vector),
    ``angle_to_previous_deg``), ``coverage`` (``positions``,
    ``distinct_positions``, ``covered`` and ``missing`` of the 26 cube
    directions (by what points down), ``axes``, ``verdict``,
    ``observability``, ``problems``, ``advice``, ``summary``),
    ``detection`` (``quiet_level`` and ``threshold`` in ``units``,
    ``still_fraction``, ``longest_still_s``, ``sample_period_s``, ...);
    and besides: ``outcome`` (a :class:`Finding` whose ``kind`` is
    "found", "never_still", "too_short" or "all_clipped", with the figures
    behind it: ``span_s``, ``longest_still_s``, ``quiet_level``,
    ``threshold``, ... and ``advice``: the keyword arguments that would
    change it) and ``findings`` (:class:`Finding` objects: a position
    dropped, a sensor never still; also issued as :class:`MpcalWarning`).
    """
    defaults = {k: _CALIBRATE_DEFAULTS[k] for k in _DETECT_KEYS}
    options = _options("detect", options, defaults)
    arrays = {"t": _shaped("t", t, 1), "accel": _shaped("accel", accel, 3)}
    _same_length(**arrays)
    g = 9.80665 if gravity is None else float(gravity)
    result = _reading(_mpcal._detect, arrays, arrays["t"], arrays["accel"], units, g,
                      options)
    findings = _findings(result.pop("findings"))
    outcome = Finding(**result.pop("outcome"))
    section = Section(result)
    section.findings, section.outcome = findings, outcome
    _warn(findings)
    return section


_SIMULATE_STATIC_DEFAULTS = _mpcal._simulate_static_defaults()


class Simulation:
    """A simulated session (:func:`simulate_static`) and its truth.

    t (N, s), accel (N×3, in ``units``), gyro (N×3 rad/s, or None):
    read-only arrays; truth: a :class:`Calibration` such that
    ``truth.correct(accel)`` is the true specific force (m/s²) up to the
    noise; still_ranges (K×2 row indices, end excluded) and directions (K×3
    unit vectors, the gravity reaction in the sensor frame) of the
    positions; noise_std_mps2 (3, per-sample white-noise σ); rate_hz.
    """

    def __init__(self, recording, truth, still_ranges, directions, noise_std_mps2,
                 rate_hz):
        self.recording = recording
        self.t, self.accel, self.gyro = recording.t, recording.accel, recording.gyro
        self.units = recording.units
        self.truth = Calibration(truth)
        self.still_ranges = still_ranges
        self.directions = directions
        self.noise_std_mps2 = np.asarray(noise_std_mps2)
        self.rate_hz = rate_hz

    def __repr__(self):
        return (f"<mpcal.Simulation {len(self.t)} rows at {self.rate_hz:g} Hz, "
                f"{len(self.still_ranges)} positions, units {self.units}>")


def simulate_static(**options):
    """Simulate a hand-held multi-position session with known errors, as
    ``mpcal simulate static`` does (docs/method.md §6).

    Options (defaults in parentheses): ``preset`` ("mti-g"; also
    "colibri", "inertiacube3": the paper's devices), ``seed`` (1: the same
    session on every machine), ``positions`` (26: the cube directions, then
    random ones), ``tilt_deg`` (5.0, largest hand tilt), ``dwell_s`` (10.0
    s still per position), ``turn_s`` (2.0 s per turn), ``initial_rest_s``
    (10.0 s), ``rate_hz`` (0: the device's), ``units`` ("mps2", "g",
    "counts"), ``counts_per_mps2`` (400.0) and ``counts_offset`` (32768.0)
    for counts, ``gyro`` (False: also simulate a gyroscope), ``gravity``
    (9.80665 m/s²).

    Returns a :class:`Simulation`. Raises :class:`Error` (kind "option") for
    an unknown preset or an option out of range.
    """
    options = _options("simulate_static", options, _SIMULATE_STATIC_DEFAULTS)
    return Simulation(*_mpcal._simulate_static(options))


def simulate_noise(preset="consumer", duration_s=3600.0, rate_hz=100.0, seed=1):
    """Simulate a still record with known noise terms, as ``mpcal simulate
    noise`` does: per axis white noise, bias instability (flicker) and
    random walk, on gravity along +z and a small gyroscope bias.

    preset : "consumer" (phone/drone MEMS) or "industrial"; duration_s (s);
    rate_hz (Hz); seed (the same record on every machine).

    Returns ``(recording, truth)``: a :data:`Recording` (``t`` s, ``accel``
    m/s², ``gyro`` rad/s) and the true terms per axis (x, y, z), e.g.
    ``truth["accelerometer"]["white_noise_mps2_per_rthz"]``.
    """
    return _mpcal._simulate_noise(str(preset), float(duration_s), float(rate_hz),
                                  int(seed))


_NOISE_DEFAULTS = _mpcal._noise_defaults()


def noise(t, accel, gyro=None, units="mps2", gyro_units="rads", gravity=None,
          **options):
    """The noise of a still record, as ``mpcal noise --json`` writes it:
    the overlapping Allan deviation of every axis with its confidence band,
    and the noise terms (quantisation, white noise, bias instability,
    random walk, rate ramp) each with its interval and the τ region it was
    fitted in.

    t : array (N,), seconds, evenly sampled; accel : array (N, 3) in
    ``units`` ("mps2" or "g"; raw counts have no unit: correct them first);
    gyro : array (N, 3) in ``gyro_units`` ("rads" or "dps"), optional;
    gravity : float (m/s², default 9.80665), to check the units by.

    Options: ``whole`` (False: when the sensor moved, the longest still
    part found by detection is analysed; True: every sample),
    ``confidence`` (0.683: the level of the intervals), and the static
    detection's options of :func:`detect`.

    Returns a :class:`Section` of the mpcal.noise/1 document: ``segment``
    (the rows analysed), ``rate_hz``, ``record_s``, ``accelerometer`` and
    ``gyroscope`` (per axis: ``tau_s``, the Allan deviation and its band in
    the sensor's SI units, the terms with their intervals and regions), and
    the record lengths that would measure the terms only bounded.
    """
    defaults = {k: _CALIBRATE_DEFAULTS[k] for k in _DETECT_KEYS}
    defaults.update(_NOISE_DEFAULTS)
    options = _options("noise", options, defaults)
    arrays = {"t": _shaped("t", t, 1), "accel": _shaped("accel", accel, 3),
              "gyro": None if gyro is None else _shaped("gyro", gyro, 3)}
    _same_length(**arrays)
    g = 9.80665 if gravity is None else float(gravity)
    whole = bool(options.pop("whole"))
    confidence = float(options.pop("confidence"))
    return Section(_reading(_mpcal._noise, arrays, arrays["t"], arrays["accel"],
                            arrays["gyro"], units, gyro_units, g, whole, confidence,
                            options))


def load_calibration(path):
    """Read a calibration file (mpcal.accelerometer/1 or mpcal.imu/1) into a
    :class:`Calibration`. Raises :class:`Error` (kind "format", "input" or
    "io") for an unreadable or malformed file."""
    calibration = Calibration(_mpcal._load_calibration(str(path)))
    calibration._path = str(path)
    return calibration


_NOTE_WORDS = {
    "not_measured": "{q} was not measured (not in what was given); the file holds "
                    "{v}, labelled so on its line",
    "upper_bound": "{q} was not measured; the file has its upper bound {v} (labelled "
                   "in a comment){more}",
    "term_dropped": "the format cannot hold {q} (largest entry {v}); dropped",
    "comment_only": "the format has no key for {q} (largest entry {v}): written in "
                    "the file's comments only (the tool estimates its own)",
    "frame_rotated": "{q}: the format's frame is not mpcal's; output corrected by "
                     "this file is rotated by {v} ({deg:.4g} deg) from mpcal's",
    "approximated": "{q} held approximately; a corrected reading differs from "
                    "mpcal's by up to {v}",
}


def _note_finding(note, file):
    """An export's or import's note (what the file could not carry) as a
    :class:`Finding`, worded as ``mpcal export`` words it."""
    v = f"{note['magnitude']:.4g}" + (f" {note['unit']}" if note["unit"] else "")
    more = ""
    if note["record_needed_s"] is not None:
        more = f"; record at least {note['record_needed_s']:.4g} s to measure it"
    message = f"{file}: " + _NOTE_WORDS[note["kind"]].format(
        q=note["quantity"], v=v, more=more, deg=math.degrees(note["magnitude"]))
    figures = {k: note[k] for k in ("quantity", "magnitude", "unit", "record_needed_s")}
    return Finding(note["kind"], message, figures=figures)


def export_formats():
    """The other tools' files :func:`export` writes and
    :func:`import_calibration` reads: a list of dicts with ``name`` (as
    ``format``), ``file`` (the tool's file), ``calibration`` and ``noise``
    (whether export uses them: "required", "optional" or "unused"),
    ``needs_gyroscope``, ``writes`` and ``reads``."""
    return _mpcal._formats()


def _is_path(value):
    return isinstance(value, (str, bytes)) or hasattr(value, "__fspath__")


def export(format, calibration=None, noise=None, path=None, *, rostopic="/imu0",
           rate_hz=None):
    """The calibration and the noise in another tool's own file, as ``mpcal
    export FORMAT ... -o PATH`` writes it (the same text, byte for byte).

    format : str
        "kalibr", "openvins", "imu-tk", ... (:func:`export_formats`).
    calibration : Calibration or path, optional
        A :class:`Calibration` (named in the file's comments by the file it
        was loaded from or saved to, else "<calibration>"), or the path of
        a calibration file (named as given).
    noise : mapping or path, optional
        The result of :func:`noise` (named "<noise>"), or the path of a
        noise file (``mpcal noise --json``).
    path : path, optional
        Where to write the file, whole or not at all (a temporary file
        renamed into place); refused when it is one of the inputs. None:
        nothing written.
    rostopic : str
        The IMU's topic, where the file names one.
    rate_hz : float, optional
        The IMU's sample rate (Hz) where the file wants one (default: the
        noise's).

    Returns the file's text. What the file cannot carry (a value not
    measured, a term the format has no place for, a frame that differs) is
    issued as :class:`MpcalWarning`, each with its :class:`Finding`
    (``quantity``, ``magnitude``, ``unit``). Raises :class:`Error` when the
    format needs what was not given (kind "input"), the format is unknown
    (kind "option"), or a file cannot be read or written.
    """
    cal_native, cal_name, read_cal = None, "", False
    if isinstance(calibration, Calibration):
        cal_native = calibration._native
        cal_name = calibration._path or "<calibration>"
    elif calibration is not None:
        if not _is_path(calibration):
            raise Error(f"calibration: {type(calibration).__name__} is neither a "
                        f"Calibration nor a path", kind="input")
        cal_name, read_cal = os.fsdecode(calibration), True
    noise_json, noise_name, read_noise = None, "", False
    if noise is not None:
        if _is_path(noise):
            noise_name, read_noise = os.fsdecode(noise), True
        elif isinstance(noise, Mapping):
            data = noise.to_dict() if isinstance(noise, Section) else dict(noise)
            noise_json, noise_name = json.dumps(data), "<noise>"
        else:
            raise Error(f"noise: {type(noise).__name__} is neither the result of "
                        f"mpcal.noise nor a path", kind="input")
    if rate_hz is not None:
        rate_hz = float(rate_hz)
        if not (math.isfinite(rate_hz) and rate_hz > 0):
            raise Error(f"rate_hz: {rate_hz} is not a sample rate (Hz); give a "
                        f"positive number", kind="option", advice={"rate_hz": None})
    output = "" if path is None else os.fsdecode(path)
    text, notes = _mpcal._export(str(format), cal_native, cal_name, read_cal, noise_json,
                                 noise_name, read_noise, str(rostopic), rate_hz, output)
    _warn(_note_finding(n, output or str(format)) for n in notes)
    return text


def import_calibration(format, *paths, units="mps2", gyro_units="rads", gravity=None):
    """Another tool's calibration as a :class:`Calibration` without 1σ, as
    ``mpcal import FORMAT PATHS... -o CALIB.json`` reads it.

    format : str
        "imu-tk", "kalibr-scale-misalignment", ... (:func:`export_formats`,
        those that read).
    paths : paths
        The tool's file(s), in the order the format takes them (imu_tk:
        the accelerometer's .calib, then the gyroscope's).
    units, gyro_units : str
        Units of the raw readings the tool's parameters apply to: "mps2",
        "g" or "counts"; "rads", "dps" or "counts".
    gravity : float, optional
        The gravity magnitude the calibration holds for (m/s², default
        9.80665).

    What mpcal's model could not hold is issued as :class:`MpcalWarning`.
    Raises :class:`Error` naming the file, the key and what is wrong.
    """
    if not paths:
        raise Error("import_calibration: give the tool's file(s) after the format",
                    kind="input")
    names = [os.fsdecode(p) for p in paths]
    g = 9.80665 if gravity is None else float(gravity)
    if not math.isfinite(g):
        raise Error(f"gravity: {gravity} is not a number of m/s²", kind="option",
                    advice={"gravity": None})
    provenance = (f"mpcal.import_calibration({str(format)!r}, "
                  f"{', '.join(repr(n) for n in names)}, units={units!r}, "
                  f"gyro_units={gyro_units!r}, gravity={g!r})")
    native, notes = _mpcal._import(str(format), names, str(units), str(gyro_units), g,
                                   provenance)
    findings = [_note_finding(n, names[0]) for n in notes]
    _warn(findings)
    return Calibration(native, findings)


class Section(Mapping):
    """A block of a result file (a calibration, a detection) read as a
    mapping and by attribute: numbers as floats, lists of numbers as numpy
    arrays, blocks as Sections. The keys carry their units as the file's
    do. ``to_dict()`` gives the JSON's Python objects."""

    def __init__(self, data):
        self._data = data

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return _value(self._data[name])
        except KeyError:
            raise AttributeError(f"no '{name}' in this block; it has: "
                                 f"{', '.join(self._data)}") from None

    def __getitem__(self, name):
        return _value(self._data[name])

    def __dir__(self):
        return list(self._data)

    def __iter__(self):
        return iter(self._data)

    def __len__(self):
        return len(self._data)

    def to_dict(self):
        """The section as plain Python objects (dicts, lists, numbers: the
        JSON document's own units), a copy of its own."""
        return json.loads(json.dumps(self._data))

    def __repr__(self):
        return f"Section({self._data!r})"


def _value(v):
    if isinstance(v, dict):
        return Section(v)
    if isinstance(v, list) and v and all(isinstance(x, (int, float)) and
                                          not isinstance(x, bool) for x in v):
        return np.array(v, dtype=np.float64)
    if isinstance(v, list) and v and all(isinstance(x, list) for x in v):
        try:
            return np.array(v, dtype=np.float64)
        except (TypeError, ValueError):
            pass
    if isinstance(v, list):
        return [_value(x) for x in v]
    return v


class Calibration:
    """A calibration, as :func:`calibrate` makes it or
    :func:`load_calibration` reads it. Its attributes mirror the calibration
    file (docs/formats.md), with the file's names and units:

    bias_mps2 (3,), scale_factor_error (3, dimensionless), non_orthogonality_rad
    (a Section with yz, zx, zy), gravity_mps2, model, input (units,
    mps2_per_unit, ...), std (the same parameters' 1σ), fit (residuals,
    variance factor, split_half, ...), positions (one Section per static
    position), warnings, gyroscope (m (3×3), bias_radps, std, fit, ... or
    None), provenance; bias_drift_mps2_per_s when the session showed one;
    findings (the warnings as :class:`Finding` objects).
    """

    def __init__(self, native, findings=()):
        self._native = native
        self._file = json.loads(native._json())
        self._path = None
        #: Each of ``warnings`` as a :class:`Finding` (a calibration made by
        #: :func:`calibrate`; empty for one read from a file, whose warnings
        #: are sentences only).
        self.findings = _findings(findings)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return _value(self._file[name])
        except KeyError:
            raise AttributeError(f"the calibration has no '{name}'; it has: "
                                 f"{', '.join(self._file)}") from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._file))

    @property
    def bias_mps2(self):
        """Accelerometer bias (m/s²), x, y, z: the reading at zero specific
        force, in nominal m/s²."""
        return _value(self._file["bias_mps2"])

    @property
    def scale_factor_error(self):
        """Scale-factor errors (dimensionless: 0.001 is 1000 ppm), x, y, z."""
        return _value(self._file["scale_factor_error"])

    @property
    def non_orthogonality_rad(self):
        """Non-orthogonality angles (rad): yz, zx, zy."""
        return _value(self._file["non_orthogonality_rad"])

    @property
    def std(self):
        """1σ of each parameter, with the same names and units (None for a
        truth file)."""
        return _value(self._file["std"]) if "std" in self._file else None

    @property
    def gyroscope(self):
        """The gyroscope's calibration (m: 3×3, bias_radps, std, fit,
        position_bias, ...) or None for an accelerometer alone."""
        g = self._file.get("gyroscope")
        return None if g is None else _value(g)

    @property
    def split_half(self):
        """The split-half check (fit.split_half): the halves' z per parameter,
        χ², p-value, the widening applied to every 1σ; None when absent."""
        s = self._file.get("fit", {}).get("split_half")
        return None if s is None else _value(s)

    @property
    def input_units(self):
        """Units of the readings this calibration corrects: "mps2", "g",
        "counts"."""
        return self._file["input"]["units"]

    def to_dict(self):
        """The calibration file's JSON as Python objects."""
        return json.loads(json.dumps(self._file))

    def correct(self, accel, gyro=None, units=None, gyro_units=None):
        """Correct readings: returns ``(accel_mps2, gyro_radps)``, N×3 each
        (``gyro_radps`` None without ``gyro``).

        accel : array (N, 3) in ``units`` (default: the calibration's input
            units; "mps2" and "g" convert into each other, counts need a
            calibration made in counts).
        gyro : array (N, 3) in ``gyro_units`` (default: the units the
            calibration was made in); corrected with the gyroscope's M, bias
            and g-sensitivity (from the corrected specific force).
        """
        accel = _rows("accel", accel, 3)
        if gyro is not None:
            gyro = _rows("gyro", gyro, 3)
            _same_length(accel=accel, gyro=gyro)
        if units is None:
            units = self.input_units
        if gyro_units is None:
            g = self._file.get("gyroscope")
            gyro_units = g["input"]["units"] if g else "rads"
        return self._native._correct(accel, gyro, units, gyro_units)

    def save(self, path):
        """Write the calibration file (JSON) to ``path``, whole or not at
        all (a temporary file renamed into place). Raises :class:`Error`
        (kind "io") when it cannot be written."""
        self._native._save(str(path))
        self._path = str(path)

    def __repr__(self):
        b = ", ".join(f"{x:.6g}" for x in self._file["bias_mps2"])
        return (f"<mpcal.Calibration {self._file['format']} {self._file['model']}: "
                f"bias_mps2 [{b}]>")
