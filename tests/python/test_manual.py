"""help(mpcal) is a manual: every public function, class, method and
property has a docstring, the type stubs declare every public name, and
__version__ is the project's."""
import ast
import inspect
import pathlib
import re

import mpcal

ROOT = pathlib.Path(__file__).resolve().parents[2]


def public_objects():
    for name in mpcal.__all__:
        if name == "__version__":
            continue
        obj = getattr(mpcal, name)
        yield name, obj
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if not member.startswith("_") and (callable(value) or
                                                   isinstance(value, property)):
                    yield f"{name}.{member}", value


def test_every_public_name_has_a_docstring():
    undocumented = [name for name, obj in public_objects()
                    if not (getattr(obj, "__doc__", None) or "").strip()]
    assert undocumented == []


def test_the_functions_on_arrays_give_their_units():
    # The arrays' units are in the words of each docstring.
    for function in (mpcal.detect, mpcal.calibrate, mpcal.noise):
        doc = function.__doc__
        assert re.search(r"seconds|\(s\)", doc) and "(N, 3)" in doc, function.__name__
        assert '"mps2"' in doc and '"g"' in doc, function.__name__


def test_the_stubs_declare_every_public_name():
    stubs = ast.parse(pathlib.Path(mpcal.__file__).with_suffix(".pyi").read_text())
    declared = set()
    for node in stubs.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            declared.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            declared.add(node.target.id)
        elif isinstance(node, ast.Assign):
            declared.update(t.id for t in node.targets if isinstance(t, ast.Name))
    assert set(mpcal.__all__) - declared == set()


def test_version_is_the_projects():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    assert mpcal.__version__ == re.search(r"project\(mpcal VERSION ([0-9.]+)", cmake)[1]
