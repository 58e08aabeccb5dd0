"""Fixtures of the Python module's tests (run by ctest: Python.module).

The module is found on PYTHONPATH (build/python); GRANASYM_SOURCE_DIR is the
repository and GRANASYM_PROGRAM the built command-line program, which some
tests compare the module with.
"""
import os
import pathlib

import pytest

import granasym

DATA = pathlib.Path(__file__).parent / "data"


def source_dir():
    return pathlib.Path(os.environ.get("GRANASYM_SOURCE_DIR", DATA.parent.parent.parent))


@pytest.fixture(scope="session")
def scene_run(tmp_path_factory):
    """The tiny scene run once: (its summary, the progress reports, the result path)."""
    out = tmp_path_factory.mktemp("scene") / "run.h5"
    reports = []
    summary = granasym.run_scene(str(DATA / "tiny_scene.toml"), str(out), progress=reports.append)
    return summary, reports, out


@pytest.fixture(scope="session")
def study_run(tmp_path_factory):
    """The one-case programme run once at the tiny scale: (its outcome, the folder)."""
    out = tmp_path_factory.mktemp("study") / "one-case"
    outcome = granasym.run_programme(str(DATA / "one_case.toml"), "tiny", str(out), jobs=1,
                                     threads=1)
    return outcome, out


# London clay (constitutive/examples/london_clay_isochoric.toml).
LONDON_CLAY = {"phi_c_deg": 22.6, "lambda_star": 0.11, "kappa_star": 0.016,
               "n_intercept": 1.375, "r": 0.4}
