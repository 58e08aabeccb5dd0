"""The module itself: what it holds and its errors."""
import os

import granasym


def test_the_module_holds_the_three_jobs():
    names = ["read_result", "read_state_table", "run_scene", "run_programme"]
    # Built with the models (the default; ctest says which):
    if os.environ.get("GRANASYM_PYTHON_MODELS", "1") == "1":
        names += ["read_calibration", "Model", "model_parameters", "calibrate"]
    for name in names:
        assert hasattr(granasym, name), name
    assert granasym.__version__


def test_errors_are_python_exceptions_of_the_right_kind():
    assert issubclass(granasym.InputError, ValueError)
    assert issubclass(granasym.FileError, granasym.RuntimeError)
    assert issubclass(granasym.FileError, OSError)
    assert issubclass(granasym.RuntimeError, RuntimeError)
