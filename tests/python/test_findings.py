"""Findings as objects: a kind, the figures in SI units, the keyword
arguments that would change them; issued as mpcal.MpcalWarning with the
finding attached."""
import warnings

import numpy as np
import pytest

import mpcal


# The calibration's parameters, as the solver names them.
PARAMETERS = {"bias_x_mps2", "bias_y_mps2", "bias_z_mps2", "scale_factor_error_x",
              "scale_factor_error_y", "scale_factor_error_z", "theta_yz_rad",
              "theta_zx_rad", "theta_zy_rad"}


@pytest.fixture(scope="module")
def session():
    return mpcal.simulate_static(seed=3)


def calibrate_caught(*args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cal = mpcal.calibrate(*args, **kwargs)
    return cal, [w.message for w in caught if issubclass(w.category, mpcal.MpcalWarning)]


def test_a_bumped_position_is_an_outlier_finding(session):
    # The sixth position held 0.05 m/s² off along gravity (a lean on the
    # table): far beyond its noise averaged over 10 s (about 0.5 mm/s²).
    accel = np.array(session.accel)
    begin, end = session.still_ranges[5]
    accel[begin:end] += 0.05 * session.directions[5]
    cal, caught = calibrate_caught(session.t, accel)
    outliers = [f for f in cal.findings if f.kind == mpcal.FindingKind.OUTLIER_EXCLUDED]
    assert len(outliers) == 1
    f = outliers[0]
    assert f.kind == "outlier_excluded"  # a str too
    # Its times are the bumped position's, trimmed by the settling.
    assert session.t[begin] <= f.start_s < f.end_s <= session.t[end - 1]
    assert f.end_s - f.start_s > 8.0
    assert f.position == 6  # after the initial rest and five positions
    # The offset over its noise averaged over the position: about 90.
    assert 40 < f.residual_z < 200
    assert f.message.startswith(f"position {f.position + 1} (")
    # The finding is the file's warning sentence, and the warning carries it.
    assert f.message in cal.warnings
    assert [w.finding for w in caught] == cal.findings
    assert str(caught[0]) == caught[0].finding.message
    with pytest.raises(AttributeError, match="residual_z"):
        f.no_such_figure


def test_positions_without_redundancy(session):
    # The rest and the first eight positions: nine positions for nine
    # parameters, none to spare.
    end = session.still_ranges[7][1] + 10
    cal, caught = calibrate_caught(session.t[:end], session.accel[:end])
    assert cal.fit.positions == 9
    kinds = [f.kind for f in cal.findings]
    assert kinds.count("no_redundancy") == 1
    for f in cal.findings:
        assert isinstance(f.kind, mpcal.FindingKind)
        if f.kind in ("no_redundancy", "poorly_determined"):
            # What helps is more positions, shown by mpcal.detect.
            assert f.advice == {} and f.stage == "detect"
        if f.kind == "no_redundancy":
            assert (f.positions, f.parameters) == (9, 9)
        if f.kind == "poorly_determined":
            assert f.parameter in PARAMETERS
    assert len(caught) == len(cal.findings) == len(cal.warnings)


def test_detect_outcome_and_findings_are_findings(session):
    d = mpcal.detect(session.t, session.accel, min_static_s=30)
    assert isinstance(d.outcome, mpcal.Finding)
    assert d.outcome.kind == "too_short"
    assert d.outcome.longest_still_s == pytest.approx(10, abs=1)
    assert d.outcome.span_s == pytest.approx(session.t[-1] - session.t[0], rel=1e-9)
    assert 0 < d.outcome.advice["min_static_s"] < 10


def test_a_clipped_position_is_a_finding(session):
    # Every reading beyond 9.5 m/s² held at 9.5 (a ±9.5 m/s² sensor): the
    # positions with an axis along gravity are clipped and dropped.
    accel = np.clip(session.accel, -9.5, 9.5)
    with pytest.warns(mpcal.MpcalWarning) as caught:
        d = mpcal.detect(session.t, accel, range_g=9.5 / 9.80665)
    clipped = [f for f in d.findings if f.kind == "clipped_position"]
    assert clipped and all(f.clipped_samples > 0 for f in clipped)
    assert all(f.end_s > f.start_s for f in clipped)
    assert {w.message.finding.kind for w in caught} >= {"clipped_position"}


def test_reader_sentences_are_log_findings(tmp_path):
    log = tmp_path / "dup.csv"
    rows = ["t,ax,ay,az"] + [f"{i / 100:.2f},0,0,9.8" for i in range(50)]
    rows.insert(10, rows[10])
    log.write_text("\n".join(rows) + "\n")
    with pytest.warns(mpcal.MpcalWarning) as caught:
        mpcal.read_log(log)
    assert caught[0].message.finding.kind == mpcal.FindingKind.LOG
    assert "duplicate" in caught[0].message.finding.message
