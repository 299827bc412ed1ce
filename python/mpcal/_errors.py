"""mpcal's exception, finding and warning classes (raised from the library's
C++ too)."""
import enum


class Error(ValueError):
    """Bad input to mpcal: a malformed log, an unusable session, an option out
    of range, an array of the wrong shape, dtype or with a non-finite value,
    or a file that cannot be read or written.

    ``str(error)`` is a plain sentence: what was wrong and where. What would
    fix it is carried as facts:

    kind : str
        "input", "io", "option", "columns", "units", "time", "format" or
        "session".
    advice : dict
        The keyword arguments the message speaks of, with the values the
        data suggest: ``{"units": "g"}``, ``{"min_static_s": 1.1,
        "settle_s": 0.15, "threshold": None}``; None is a value of the
        caller's choosing. The message says how they combine.
    stage : str or None
        An mpcal function to run to see more ("detect", ...), on
        ``stage_input`` when that is not empty.
    figures : dict
        The figures behind the finding, for the kinds that have them (units:
        "median_magnitude" in the given units, "gravity_mps2", "looks_like";
        session: "problem", "positions", "longest_still_s",
        "still_fraction"; a value that is NaN or infinite: "argument", "row"
        (the first, 0-based), "rows" (how many hold one)).
    """

    def __init__(self, message, kind="input", advice=None, stage=None,
                 stage_input="", figures=None):
        super().__init__(message)
        self.kind = kind
        self.advice = dict(advice or {})
        self.stage = stage
        self.stage_input = stage_input
        self.figures = dict(figures or {})

    def __reduce__(self):
        return (type(self), (str(self), self.kind, self.advice, self.stage,
                             self.stage_input, self.figures))


class FindingKind(str, enum.Enum):
    """What a :class:`Finding` is about. A ``str`` too:
    ``finding.kind == "outlier_excluded"`` holds."""

    #: A log reader's sentence (a gap in time, duplicated stamps, a cut
    #: line, two streams that do not line up); figures: none.
    LOG = "log"
    #: Detection: a position dropped, its readings at the sensor's range
    #: limit (``start_s``, ``end_s``, ``clipped_samples``, ``clip_limits``).
    CLIPPED_POSITION = "clipped_position"
    #: Detection: even the quietest part moves more than a still sensor
    #: (``quiet_g``, ``quiet_quantile``, ``plausible_quiet_g``).
    NOT_STILL = "not_still"
    #: The fit left a position out: it fits far beyond its noise
    #: (``position`` 0-based, ``start_s``, ``end_s``, ``residual_z``).
    OUTLIER_EXCLUDED = "outlier_excluded"
    #: A position fitting far beyond its noise kept: without it the others
    #: do not determine the parameters (figures as OUTLIER_EXCLUDED).
    OUTLIER_KEPT = "outlier_kept"
    #: A parameter strongly correlated with others (``parameter``).
    POORLY_DETERMINED = "poorly_determined"
    #: As many positions as parameters: nothing checks the fit
    #: (``positions``, ``parameters``).
    NO_REDUNDANCY = "no_redundancy"
    #: Two halves of the positions differ beyond their 1σ; every 1σ is
    #: widened (``split``, ``positions_first``, ``positions_second``,
    #: ``rms_z``, ``dof``, ``p_value``, ``widening``).
    HALVES_DISAGREE = "halves_disagree"
    #: The gyroscope could not be calibrated (the library's reason in the
    #: message).
    GYROSCOPE_NOT_CALIBRATED = "gyroscope_not_calibrated"
    GYROSCOPE_NOT_CONVERGED = "gyroscope_not_converged"
    #: The turns are too few for M (``turns``, ``turns_needed``,
    #: ``turn_axes``: the axes to turn about).
    GYROSCOPE_TOO_FEW_TURNS = "gyroscope_too_few_turns"
    #: The turns leave entries of M undetermined or poorly determined
    #: (``parameters``, ``std``, ``std_limit``, ``turn_axes``).
    GYROSCOPE_UNDETERMINED = "gyroscope_undetermined"
    GYROSCOPE_POORLY_DETERMINED = "gyroscope_poorly_determined"
    #: Export: a value the format wants and mpcal did not measure, held as
    #: ``magnitude`` (in ``unit``) on a labelled line (``quantity``).
    NOT_MEASURED = "not_measured"
    #: Export: a noise value not measured on its axis, its upper bound
    #: written (``magnitude``, ``unit``; ``record_needed_s`` to measure it).
    UPPER_BOUND = "upper_bound"
    #: Export or import: a term the format cannot hold, dropped
    #: (``quantity``; ``magnitude``: its largest entry, in ``unit``).
    TERM_DROPPED = "term_dropped"
    #: Export: a value with no key in the format, written in comments only.
    COMMENT_ONLY = "comment_only"
    #: Export: the format's frame is not mpcal's; output corrected by the
    #: file is rotated by ``magnitude`` rad.
    FRAME_ROTATED = "frame_rotated"
    #: Export or import: held approximately, ``magnitude`` the largest
    #: difference to a corrected reading (in ``unit``).
    APPROXIMATED = "approximated"

    def __str__(self):
        return self.value


class Finding:
    """A finding that does not stop the work, as facts.

    kind : FindingKind
    message : str
        The plain sentence (as the result's ``warnings`` and the command
        say it).
    advice : dict
        The keyword arguments that would change it, with the values the data
        suggest (None: the caller's to choose); empty when it is the
        session that would (record more positions or turns).
    stage : str or None
        An mpcal function to run to see more ("detect").
    figures : dict
        The figures behind it, in SI units with the units in their names,
        also readable as attributes (``finding.residual_z``).
    """

    def __init__(self, kind, message, advice=None, stage=None, figures=None):
        try:
            self.kind = FindingKind(kind)
        except ValueError:
            self.kind = kind
        self.message = message
        self.advice = dict(advice or {})
        self.stage = stage
        self.figures = dict(figures or {})

    def __getattr__(self, name):
        if name.startswith("_") or name == "figures":
            raise AttributeError(name)
        try:
            return self.figures[name]
        except KeyError:
            raise AttributeError(f"this {self.kind} finding has no '{name}'; its "
                                 f"figures: {', '.join(self.figures) or 'none'}") from None

    def __str__(self):
        return self.message

    def __repr__(self):
        return f"<mpcal.Finding {self.kind}: {self.message}>"

    def __eq__(self, other):
        return (isinstance(other, Finding) and
                (self.kind, self.message, self.advice, self.stage, self.figures) ==
                (other.kind, other.message, other.advice, other.stage, other.figures))

    __hash__ = None


class MpcalWarning(UserWarning):
    """A finding that does not stop the work (a position dropped, a gap in
    time, a poorly determined parameter), issued through Python's warnings
    module; ``warning.finding`` is the :class:`Finding`, and the same
    findings are in the result's ``findings``."""

    def __init__(self, finding):
        if not isinstance(finding, Finding):
            finding = Finding("log", str(finding))
        super().__init__(finding.message)
        self.finding = finding


# Shown as mpcal.Error and mpcal.MpcalWarning in tracebacks and help().
Error.__module__ = "mpcal"
MpcalWarning.__module__ = "mpcal"
Finding.__module__ = "mpcal"
FindingKind.__module__ = "mpcal"
