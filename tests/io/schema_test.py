#!/usr/bin/env python3
"""Every JSON file mpcal writes holds to its schema in docs/schemas/.

Runs the commands on simulated sessions and the bundled recordings, and
validates each file they write against the schema its `format` names (and
checks that it names the format expected of it); validates every checked-in
file in tests/data/ that claims one of these formats; and validates broken
copies that the schemas must refuse, so that a schema that accepts anything
fails here too. The schemas are strict: a field a writer adds without a
schema change fails this test.

Needs Debian's python3-jsonschema (4.10 or later: draft 2020-12).

usage: schema_test.py MPCAL_BINARY PROJECT_ROOT WORK_DIR
"""
import copy
import json
import math
import pathlib
import shutil
import subprocess
import sys

from jsonschema import Draft202012Validator

FAMILIES = ["mpcal.accelerometer", "mpcal.imu", "mpcal.detection",
            "mpcal.repeatability", "mpcal.verification", "mpcal.noise",
            "mpcal.noise_truth", "mpcal.inspection"]

# Checked-in files made to be refused, and where the schema must find the
# fault: a path into the document (a missing field: its name), or "parse"
# for a file that is not JSON mpcal could read at all.
REFUSED = {
    "bad_calib_missing_bias.json": "bias_mps2",
    "bad_calib_model.json": "model",
    "bad_calib_nan.json": "parse",
    "bad_calib_scale.json": "input/mps2_per_unit",
    "bad_calib_syntax.json": "parse",
    "bad_calib_type.json": "gravity_mps2",
    "bad_calib_version2.json": "format",
    "bad/malformed.json": "parse",
    "bad/nonfinite.json": "parse",
    "bad/not_an_object.json": "",
    "bad/null_value.json": "bias_mps2/1",
    "bad/version2.json": "format",
}

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def reject_constant(name):
    raise ValueError(f"{name} is not JSON")


def finite_float(text):
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is not a finite number")
    return value


def load_json(path):
    """Strict JSON, as mpcal reads it: no NaN or Infinity, no 1e999."""
    with open(path, encoding="utf-8") as f:
        return json.load(f, parse_constant=reject_constant,
                         parse_float=finite_float)


class Schemas:
    def __init__(self, directory):
        self.by_file = {}
        for family in FAMILIES:
            name = f"{family}-1.schema.json"
            schema = load_json(directory / name)
            Draft202012Validator.check_schema(schema)
            if schema.get("$id") != name:
                fail(f"{name}: $id is {schema.get('$id')!r}, expected {name!r}")
            self.by_file[name] = schema
        for path in sorted(directory.glob("*.json")):
            if path.name not in self.by_file:
                fail(f"docs/schemas/{path.name}: not a format this test knows (FAMILIES)")
        self.validators = {}
        for name, schema in self.by_file.items():
            self.validators[name] = self._validator(schema)

    def _validator(self, schema):
        # Relative $refs between the schemas resolve against their $id (the
        # file name): jsonschema >= 4.18 resolves through a referencing
        # Registry, older ones (Debian 12's 4.10) through a RefResolver.
        try:
            from referencing import Registry, Resource
        except ImportError:
            from jsonschema import RefResolver
            return Draft202012Validator(
                schema, resolver=RefResolver.from_schema(schema, store=self.by_file))
        registry = Registry().with_resources(
            (name, Resource.from_contents(s)) for name, s in self.by_file.items())
        return Draft202012Validator(schema, registry=registry)

    def errors(self, document):
        """The schema errors of `document`, chosen by its `format`."""
        if not isinstance(document, dict) or not isinstance(document.get("format"), str):
            return [("", "not an object with a 'format' string")]
        family = document["format"].split("/")[0]
        name = f"{family}-1.schema.json"
        if name not in self.validators:
            return [("format", f"no schema for {document['format']!r}")]
        return [("/".join(str(p) for p in e.absolute_path),
                 f"{e.validator}: {e.message}")
                for e in self.validators[name].iter_errors(document)]


def family_of(document):
    fmt = document.get("format") if isinstance(document, dict) else None
    return fmt.split("/")[0] if isinstance(fmt, str) else ""


def describe(errors):
    return "; ".join(f"at '{p}': {m[:160]}" for p, m in errors[:3])


def check_written(schemas, work, name, family, must_hold=()):
    """A file a command wrote: its format, its schema, and the optional
    parts the case exists for (so that a case that stops exercising them is
    noticed)."""
    path = work / name
    failed_before = len(failures)
    if not path.is_file():
        fail(f"{name}: not written")
        return None
    try:
        document = load_json(path)
    except ValueError as e:
        fail(f"{name}: not strict JSON: {e}")
        return None
    if family_of(document) != family:
        fail(f"{name}: format {document.get('format')!r}, expected {family}/1")
    errors = schemas.errors(document)
    if errors:
        fail(f"{name} ({family}): {describe(errors)}")
    for pointer in must_hold:
        node = document
        for key in pointer.split("/"):
            node = node.get(key) if isinstance(node, dict) else None
        if node is None:
            fail(f"{name}: holds no '{pointer}', which this case is for")
    if len(failures) == failed_before:
        print(f"ok: {name} ({family})")
    return document


def run(mpcal, work, *args, exit_code=0):
    result = subprocess.run([mpcal, *args], cwd=work, capture_output=True,
                            text=True, check=False)
    if result.returncode != exit_code:
        fail(f"mpcal {' '.join(args)}: exit {result.returncode}, expected "
             f"{exit_code}: {result.stderr.strip()[:300]}")


def written_files(schemas, mpcal, root, work):
    data = root / "tests" / "data"
    xsens = data / "real" / "xsens-multiposition"
    walk = data / "real" / "rtklib-walk"
    acc, imu = "mpcal.accelerometer", "mpcal.imu"
    cases = [
        # Accelerometer-only calibrations in m/s², g and counts (a fitted
        # scale, and a datasheet's --counts-per-g), a sample-index log, a
        # drifting bias; the simulator's truth files.
        (["simulate", "static", "--preset", "colibri", "--seed", "1",
          "-o", "mps2.csv", "--truth", "mps2_truth.json"],
         [("mps2_truth.json", acc, [])]),
        (["calibrate", "mps2.csv", "-o", "mps2.json"],
         [("mps2.json", acc, ["std", "fit/split_half", "positions"])]),
        (["simulate", "static", "--preset", "colibri", "--units", "g", "--seed", "2",
          "-o", "g.csv", "--truth", "g_truth.json"],
         [("g_truth.json", acc, [])]),
        (["calibrate", "g.csv", "--units", "g", "-o", "g.json"],
         [("g.json", acc, ["input/columns"])]),
        (["simulate", "static", "--preset", "mti-g", "--units", "counts", "--seed", "3",
          "-o", "counts.csv", "--truth", "counts_truth.json"],
         [("counts_truth.json", acc, [])]),
        (["calibrate", "counts.csv", "--units", "counts", "-o", "counts.json"],
         [("counts.json", acc, ["input/scale_reference"])]),
        (["calibrate", "counts.csv", "--units", "counts", "--counts-per-g", "3922.66",
          "-o", "counts_per_g.json"],
         [("counts_per_g.json", acc, ["input/scale_reference"])]),
        (["calibrate", str(data / "loggers" / "arduino_mpu6050_serial.txt"),
          "--units", "counts", "--counts-per-g", "16384", "-o", "mpu6050.json"],
         [("mpu6050.json", acc, ["input/scale_reference"])]),
        (["calibrate", str(data / "loggers" / "adxl345_sample_index.txt"),
          "--units", "g", "--rate", "100", "-o", "adxl345.json"],
         [("adxl345.json", acc, ["input/rate_hz"])]),
        (["simulate", "static", "--preset", "mti-g", "--bias-drift", "2e-4",
          "-o", "warm.csv", "--truth", "warm_truth.json"],
         [("warm_truth.json", acc, [])]),
        (["calibrate", "warm.csv", "-o", "warm.json"],
         [("warm.json", acc, ["bias_drift_mps2_per_s", "std/bias_drift_mps2_per_s"])]),
        # IMU calibrations: simulated, and the real Xsens recording with its
        # gyroscope in a log of its own.
        (["simulate", "static", "--preset", "colibri", "--gyro", "--seed", "3",
          "-o", "imu.csv", "--truth", "imu_truth.json"],
         [("imu_truth.json", imu, ["gyroscope"])]),
        (["calibrate", "imu.csv", "-o", "imu.json"],
         [("imu.json", imu, ["gyroscope/fit", "gyroscope/m_covariance"])]),
        (["calibrate", str(xsens / "xsens_acc.mat"), "--gyro-log",
          str(xsens / "xsens_gyro.mat"), "--units", "counts", "--gyro-units",
          "counts", "--gravity", "9.81744", "-o", "xsens_imu.json"],
         [("xsens_imu.json", imu, ["gyroscope/fit", "gyroscope/position_bias"])]),
        # Calibrations imported from another tool (no 1σ): imu_tk's own
        # calibration of the Xsens recording, and an accelerometer alone.
        (["import", "imu-tk", str(xsens / "imu_tk" / "xsens_acc.calib"),
          str(xsens / "imu_tk" / "xsens_gyro.calib"), "--units", "counts",
          "--gyro-units", "counts", "--gravity", "9.81744", "-o", "imported_imu.json"],
         [("imported_imu.json", imu, ["imported_from"])]),
        (["import", "imu-tk", str(xsens / "imu_tk" / "xsens_acc.calib"), "--units",
          "counts", "-o", "imported_acc.json"],
         [("imported_acc.json", acc, ["imported_from"])]),
        # Detection: positions found, with turns, and none found (exit 1,
        # the file is still written).
        (["detect", "mps2.csv", "--json", "detect.json"],
         [("detect.json", "mpcal.detection", ["intervals"])]),
        (["detect", str(xsens / "xsens_acc.mat"), "--gyro-log",
          str(xsens / "xsens_gyro.mat"), "--units", "counts", "--gyro-units",
          "counts", "--json", "detect_turns.json"],
         [("detect_turns.json", "mpcal.detection", ["turns"])]),
        (["detect", str(data / "detect_always_moving.csv"), "--units", "g",
          "--json", "detect_none.json"],
         [("detect_none.json", "mpcal.detection", [])], 1),
        # Repeatability: simulated power-ups (verdicts) and the paper's
        # trials (no 1σ: null verdicts).
        (["simulate", "static", "--preset", "colibri", "--seed", "7", "--trials", "3",
          "-o", "trial.csv", "--truth", "trial_truth.json"],
         [(f"trial_truth_{i}.json", acc, []) for i in (1, 2, 3)]),
        (["repeat", "trial_1.csv", "trial_2.csv", "trial_3.csv", "--json", "repeat.json"],
         [("repeat.json", "mpcal.repeatability", [])]),
        (["repeat"] + [str(data / "paper" / f"colibri_trial{i}.json") for i in (1, 2, 3)]
         + ["--json", "repeat_paper.json"],
         [("repeat_paper.json", "mpcal.repeatability", [])]),
        # Verification: a simulated walk with its truth as the calibration
        # and trajectory CSVs; the real walk without a calibration.
        (["simulate", "walk", "--preset", "colibri", "--seed", "1", "--turn",
          "-o", "turn.csv", "--gnss", "turn.pos", "--truth", "walk_truth.json"],
         [("walk_truth.json", acc, [])]),
        (["verify", "--imu", "turn.csv", "--gnss", "turn.pos", "--calib",
          "walk_truth.json", "-o", "verify.json", "--trajectory-csv", "turn"],
         [("verify.json", "mpcal.verification", ["corrected", "trajectories"])]),
        (["verify", "--imu", str(walk / "imu_1730_sf.csv"), "--columns",
          "t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6", "--units", "g", "--gnss",
          str(walk / "gnss_1730_sf.pos"), "-o", "verify_real.json"],
         [("verify_real.json", "mpcal.verification", [])]),
        # Noise: a simulated still IMU and its truth, and the bundled
        # accelerometer-only record.
        (["simulate", "noise", "--hours", "0.5", "--rate", "100", "-o", "still.csv",
          "--truth", "noise_truth.json"],
         [("noise_truth.json", "mpcal.noise_truth", [])]),
        (["noise", "still.csv", "--json", "noise.json"],
         [("noise.json", "mpcal.noise", ["gyroscope"])]),
        (["noise", str(data / "noise_still.csv"), "--json", "noise_bundled.json"],
         [("noise_bundled.json", "mpcal.noise", [])]),
        # Inspection: a recording (its IMU topic's ranges) and a text log.
        (["inspect", str(data / "bags" / "imu_lz4.bag"), "--json", "inspect_bag.json"],
         [("inspect_bag.json", "mpcal.inspection", ["recording"])]),
        (["inspect", "imu.csv", "--json", "inspect_log.json"],
         [("inspect_log.json", "mpcal.inspection", ["text_log"])]),
        # The demo's calibration and truth.
        (["demo", "--preset", "colibri", "--output-dir", "demo"],
         [("demo/calib.json", imu, []), ("demo/truth.json", imu, [])]),
    ]
    documents = {}
    for case in cases:
        args, outputs = case[0], case[1]
        run(mpcal, work, *args, exit_code=case[2] if len(case) > 2 else 0)
        for name, family, must_hold in outputs:
            documents[name] = check_written(schemas, work, name, family, must_hold)
    # The paper's trials have no 1σ: the verdicts are null, which the
    # schema must allow.
    paper = documents.get("repeat_paper.json")
    if paper and paper["parameters"]["bias_mps2"]["changed"] != [None] * 3:
        fail("repeat_paper.json: expected null verdicts (the paper gives no 1σ)")
    return documents


def checked_in_files(schemas, root):
    data = root / "tests" / "data"
    seen = set()
    for path in sorted(data.rglob("*.json")):
        rel = path.relative_to(data).as_posix()
        expected = REFUSED.get(rel)
        seen.add(rel)
        try:
            document = load_json(path)
        except ValueError as e:
            if expected != "parse":
                fail(f"tests/data/{rel}: not strict JSON: {e}")
            else:
                print(f"ok: tests/data/{rel} refused (not strict JSON)")
            continue
        claims = family_of(document) in FAMILIES
        if expected is None and not claims:
            continue  # JSON of another kind (e.g. a list of sessions)
        errors = schemas.errors(document)
        if expected is None:
            if errors:
                fail(f"tests/data/{rel}: {describe(errors)}")
            else:
                print(f"ok: tests/data/{rel} ({family_of(document)})")
        elif not any(p == expected or (m.startswith("required:") and f"'{expected}'" in m)
                     for p, m in errors):
            fail(f"tests/data/{rel}: expected refused at '{expected}', got "
                 f"{describe(errors) or 'valid'}")
        else:
            print(f"ok: tests/data/{rel} refused at '{expected}'")
    for rel in sorted(set(REFUSED) - seen):
        fail(f"tests/data/{rel}: listed as refused but not there")


def remove(doc, *path):
    node = doc
    for key in path[:-1]:
        node = node[key]
    del node[path[-1]]


def put(doc, value, *path):
    node = doc
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value


def broken_copies(schemas, documents):
    """Each edit of a written file, and whether the schema must accept it."""
    cases = {
        "mps2.json": [
            ("a required field missing", False, lambda d: remove(d, "bias_mps2")),
            ("a string where a number belongs", False,
             lambda d: put(d, "9.80665", "gravity_mps2")),
            ("a 2-vector", False, lambda d: put(d, [0.1, 0.2], "bias_mps2")),
            ("a 4-vector in a position", False,
             lambda d: put(d, [0.0, 0.0, 9.8, 0.0], "positions", 0, "mean_mps2")),
            ("a field the writer does not write", False,
             lambda d: put(d, 21.5, "temperature_c")),
            ("a field unknown in a position", False,
             lambda d: put(d, 1, "positions", 0, "temperature_c")),
            ("a bias beyond 10 g", False, lambda d: put(d, 1e308, "bias_mps2", 0)),
            ("a scale-factor error of 0.5", False,
             lambda d: put(d, 0.5, "scale_factor_error", 2)),
            ("an angle of pi/4", False,
             lambda d: put(d, 0.7853981633974483, "non_orthogonality_rad", "zx")),
            ("gravity off Earth", False, lambda d: put(d, 1.62, "gravity_mps2")),
            ("unknown units", False, lambda d: put(d, "volts", "input", "units")),
            ("m/s² units with a factor", False,
             lambda d: put(d, 9.80665, "input", "mps2_per_unit")),
            ("a negative 1σ", False, lambda d: put(d, -1e-4, "std", "bias_mps2", 1)),
            ("major version 2", False, lambda d: put(d, "mpcal.accelerometer/2", "format")),
            ("another file's format", False, lambda d: put(d, "mpcal.noise/1", "format")),
            ("minor version 1.3", True, lambda d: put(d, "mpcal.accelerometer/1.3", "format")),
            ("bias-scale-6 with an angle", False,
             lambda d: put(d, "bias-scale-6", "model")),
        ],
        "warm.json": [
            ("a drift without its reference time", False,
             lambda d: remove(d, "bias_reference_time_s")),
            ("a drift without its 1σ", False,
             lambda d: remove(d, "std", "bias_drift_mps2_per_s")),
            ("a drift's 1σ without the drift", False,
             lambda d: [remove(d, k) for k in ("bias_drift_mps2_per_s",
                                               "bias_reference_time_s",
                                               "bias_drift_p_value")]),
        ],
        "imu.json": [
            ("no gyroscope block", False, lambda d: remove(d, "gyroscope")),
            ("an 8-entry M", False, lambda d: put(d, d["gyroscope"]["m"][:8], "gyroscope", "m")),
            ("a 2-vector gyroscope bias", False,
             lambda d: put(d, [0.0, 0.0], "gyroscope", "bias_radps")),
            ("a field unknown in the gyroscope block", False,
             lambda d: put(d, 1, "gyroscope", "temperature_c")),
            ("a field added to the gyroscope's input", True,
             lambda d: put(d, "dps", "gyroscope", "input", "added_field")),
            ("the accelerometer's format with a gyroscope", False,
             lambda d: put(d, "mpcal.accelerometer/1", "format")),
            ("a field unknown at the top", False, lambda d: put(d, 1, "temperature_c")),
            ("minor version 1.1", True, lambda d: put(d, "mpcal.imu/1.1", "format")),
        ],
        "detect_turns.json": [
            ("no coverage", False, lambda d: remove(d, "coverage")),
            ("a 2-vector mean", False, lambda d: put(d, [1.0, 2.0], "intervals", 0, "mean")),
            ("an unknown verdict", False, lambda d: put(d, "fine", "coverage", "verdict")),
            ("a reading beyond any accelerometer's", False,
             lambda d: put(d, 3e9, "intervals", 0, "mean", 2)),
            ("a string turn angle", False, lambda d: put(d, "89", "turns", 0, "angle_deg")),
        ],
        "repeat.json": [
            ("trials as a string", False, lambda d: put(d, "3", "trials")),
            ("a 2-vector trial", False,
             lambda d: put(d, [0.1, 0.2], "parameters", "bias_mps2", "values", 0)),
            ("a verdict as a word", False,
             lambda d: put(d, "yes", "parameters", "non_orthogonality_rad", "yz", "changed")),
        ],
        "verify.json": [
            ("no raw path", False, lambda d: remove(d, "raw")),
            ("an unknown mount", False, lambda d: put(d, "sideways", "integration", "mount")),
            ("a string distance", False,
             lambda d: put(d, "6.8", "corrected", "horizontal_rms_m")),
        ],
        "noise.json": [
            ("no accelerometer", False, lambda d: remove(d, "accelerometer")),
            ("an unknown status", False,
             lambda d: put(d, "guessed", "gyroscope", "axes", "x",
                           "white_noise_radps_per_rthz", "status")),
            ("a measured term without its value", False,
             lambda d: remove(d, "accelerometer", "axes", "y",
                              "white_noise_mps2_per_rthz", "value")),
            ("a 2-vector mean", False, lambda d: put(d, [0.0, 9.8], "accelerometer", "mean_mps2")),
        ],
        "noise_truth.json": [
            ("a 2-vector density", False,
             lambda d: put(d, [1e-3, 1e-3], "gyroscope", "white_noise_radps_per_rthz")),
        ],
    }
    for name, edits in cases.items():
        original = documents.get(name)
        if original is None:
            fail(f"{name}: no document to break")
            continue
        if schemas.errors(original):
            continue  # already reported
        for what, accepted, edit in edits:
            broken = copy.deepcopy(original)
            edit(broken)
            errors = schemas.errors(broken)
            if accepted and errors:
                fail(f"{name} with {what}: refused, should be accepted: {describe(errors)}")
            elif not accepted and not errors:
                fail(f"{name} with {what}: accepted, should be refused")
            else:
                print(f"ok: {name} with {what}: {'accepted' if accepted else 'refused'}")


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    mpcal = sys.argv[1]
    root = pathlib.Path(sys.argv[2])
    work = pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    schemas = Schemas(root / "docs" / "schemas")
    documents = written_files(schemas, mpcal, root, work)
    checked_in_files(schemas, root)
    broken_copies(schemas, documents)
    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("every file holds to its schema; every broken copy was refused")
    return 0


if __name__ == "__main__":
    sys.exit(main())
