"""numpy for the independent generators, from Debian's python3-numpy.

The generators need numpy (Debian package python3-numpy, in
scripts/install-deps.sh). When the `python3` on PATH is not the system one (a
pyenv or venv interpreter without numpy), `need_numpy()` re-runs the calling
script once under /usr/bin/python3, where the Debian package installs it;
otherwise it stops with one line saying what to install.
"""
import os
import sys

SYSTEM_PYTHON = '/usr/bin/python3'


def need_numpy():
    try:
        import numpy  # noqa: F401
        return
    except ImportError:
        pass
    me = os.path.realpath(sys.executable or '')
    if (os.path.exists(SYSTEM_PYTHON) and me != os.path.realpath(SYSTEM_PYTHON)
            and not os.environ.get('MPCAL_INDEPENDENT_REEXEC')):
        os.environ['MPCAL_INDEPENDENT_REEXEC'] = '1'
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
    sys.exit('%s: error: numpy is missing for %s; install the Debian package python3-numpy '
             '(scripts/install-deps.sh) and run again' % (os.path.basename(sys.argv[0]), sys.executable))
