"""mpcal's exception and warning classes (raised from the library's C++ too)."""


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
        "still_fraction").
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


class MpcalWarning(UserWarning):
    """A finding that does not stop the work (a position dropped, a gap in
    time, a poorly determined parameter), issued through Python's warnings
    module; the same sentences are in the result's ``warnings``."""


# Shown as mpcal.Error and mpcal.MpcalWarning in tracebacks and help().
Error.__module__ = "mpcal"
MpcalWarning.__module__ = "mpcal"
