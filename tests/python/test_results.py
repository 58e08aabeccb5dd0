"""Runs (run_scene, run_programme) and their results read back."""
import math

import numpy as np
import pytest

import granasym
from conftest import DATA


def test_scene_runs_with_progress_and_its_result_reads_back(scene_run):
    summary, reports, out = scene_run
    assert summary["termination"] == "completed", summary["message"]
    assert summary["particles"] == 800
    assert reports, "the progress callback was never called"
    assert {"stage_name", "step", "p_kpa", "line"} <= set(reports[-1])
    result = granasym.read_result(str(out))
    assert result.final and result.note == ""
    series = result.series
    assert len(series) == summary["rows"]
    assert result.units["p_kpa"] == "kPa"
    assert series.attrs["units"]["p_kpa"] == "kPa"
    assert list(result.stages["name"]) == ["ncl", "psi90"]
    ncl = result.stages.iloc[0]
    assert ncl["stop_reason"].startswith("mean stress reached")
    # The NCL stage stops at 100 kPa: its last row is there.
    p = result.arrays["p_kpa"]
    assert isinstance(p, np.ndarray) and p.shape == (summary["rows"],)
    assert p[ncl["last_row"]] == pytest.approx(100.0, rel=0.05)
    assert "800" in result.info


def test_a_callback_that_raises_stops_the_run(tmp_path):
    class Stop(Exception):
        pass

    def progress(report):
        raise Stop(report["line"])

    out = tmp_path / "stopped.h5"
    with pytest.raises(Stop):
        granasym.run_scene(str(DATA / "tiny_scene.toml"), str(out), progress=progress)
    stopped = granasym.read_result(str(out))
    assert not stopped.final
    assert stopped.summary["termination"] == "interrupted"
    # restart=True continues it to the end.
    summary = granasym.run_scene(str(DATA / "tiny_scene.toml"), str(out), restart=True)
    assert summary["termination"] == "completed"
    assert granasym.read_result(str(out)).final


def test_bad_input_raises_input_error_with_the_message(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text((DATA / "tiny_scene.toml").read_text().replace(
        "stretching_rate = 167.0", "stretching_rate = -1.0", 1))
    with pytest.raises(granasym.InputError, match="stretching_rate"):
        granasym.run_scene(str(scene), str(tmp_path / "bad.h5"))
    with pytest.raises(granasym.InputError):
        granasym.read_result(str(scene))
    with pytest.raises(granasym.InputError, match="scale"):
        granasym.run_programme(str(DATA / "one_case.toml"), "huge", str(tmp_path / "s"))


def test_programme_runs_and_its_state_table_reads_back(study_run):
    outcome, out = study_run
    assert not outcome["interrupted"]
    cases = outcome["cases"]
    assert list(cases["status"]) == ["computed"] * len(cases)
    table = granasym.read_state_table(str(out))
    assert {"replicate", "kind", "status", "p_kpa", "e", "psi_sigma_deg"} <= set(table.columns)
    assert table["replicate"].dtype == np.int64
    assert table.attrs["units"]["p_kpa"] == "kPa"
    ncl = table[table["kind"] == "ncl"]
    assert sorted(ncl["stage"]) == ["p100", "p50"]
    for stage, p in (("p50", 50.0), ("p100", 100.0)):
        # The state is the detector window's mean; the window ends at the stop.
        row = ncl[ncl["stage"] == stage].iloc[0]
        assert row["window_p_max_kpa"] == pytest.approx(p, rel=0.1)
        assert row["window_p_min_kpa"] <= row["p_kpa"] <= row["window_p_max_kpa"]
        assert 0.3 < row["e"] < 1.5 and math.isfinite(row["psi_sigma_deg"])
    # The same table as the CSV file the study wrote.
    import pandas
    csv = pandas.read_csv(out / "asymptotic_states.csv")
    assert list(csv.columns) == list(table.columns)
    assert np.allclose(csv["p_kpa"], table["p_kpa"], rtol=1e-9)


def test_programme_run_again_computes_nothing(study_run):
    _, out = study_run
    again = granasym.run_programme(str(DATA / "one_case.toml"), "tiny", str(out), jobs=1,
                                   threads=1)
    assert set(again["cases"]["status"]) == {"cached"}
