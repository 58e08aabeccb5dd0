"""The module itself: what it holds and its errors."""
import granasym


def test_the_module_holds_the_three_jobs():
    for name in ("read_result", "read_state_table", "read_calibration", "Model",
                 "model_parameters", "calibrate", "run_scene", "run_programme"):
        assert hasattr(granasym, name), name
    assert granasym.__version__


def test_errors_are_python_exceptions_of_the_right_kind():
    assert issubclass(granasym.InputError, ValueError)
    assert issubclass(granasym.FileError, granasym.RuntimeError)
    assert issubclass(granasym.FileError, OSError)
    assert issubclass(granasym.RuntimeError, RuntimeError)
