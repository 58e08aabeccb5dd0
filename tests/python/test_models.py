"""Constitutive models: element tests, asymptotic states, ASBS sections."""
import csv
import math
import os
import subprocess
import tomllib

import numpy as np
import pytest

import granasym
from conftest import LONDON_CLAY, source_dir


def test_element_test_matches_model_run(tmp_path):
    """An example input as dicts gives the numbers of `granasym model run --csv`."""
    example = source_dir() / "constitutive" / "examples" / "london_clay_isochoric.toml"
    with open(example, "rb") as f:
        tables = tomllib.load(f)
    model_table = dict(tables["model"])
    model = granasym.Model(model_table.pop("kind"), model_table)
    run = model.element_test(tables["initial"], tables["stage"], tables["integration"])
    assert run.success, run.message
    assert run.stops[1].startswith("asymptote")
    program = os.environ.get("GRANASYM_PROGRAM")
    assert program, "GRANASYM_PROGRAM (the built granasym) is not set"
    out_csv = tmp_path / "clay.csv"
    subprocess.run([program, "model", "run", str(example), "--out", str(tmp_path / "clay.h5"),
                    "--csv", str(out_csv)], check=True, capture_output=True)
    with open(out_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    records = run.records
    assert len(records) == len(rows)
    for column in rows[0]:
        expected = np.array([float(r[column]) for r in rows])
        assert np.allclose(records[column].to_numpy(), expected, rtol=1e-12, atol=1e-12), column
    # Stage 2 is isochoric: e stays where stage 1 left it.
    e = run.arrays["e"]
    second = records["stage"].to_numpy() == 1
    assert np.ptp(e[second]) < 1e-9


def test_mixed_control_holds_the_radial_stress():
    model = granasym.Model("hypoplastic_clay", LONDON_CLAY)
    run = model.element_test(
        {"mean_stress_kpa": 100.0, "psi_sigma_deg": 0.0, "ocr": 1.0},
        [{"name": "drained", "type": "mixed", "rate": [0.1, 0.0, 0.0, 0.0, 0.0, 0.0],
          "stress_controlled": [1, 2], "duration_s": 2.0}])
    assert run.success, run.message
    assert np.allclose(run.arrays["sigma_r_kpa"], 100.0, rtol=1e-6)
    assert run.arrays["eps_a"][-1] == pytest.approx(0.2, rel=1e-9)
    # Drained shear approaches the critical state's q/p = M from below.
    sin_phi = math.sin(math.radians(LONDON_CLAY["phi_c_deg"]))
    q_over_p = run.arrays["q_kpa"][-1] / run.arrays["p_kpa"][-1]
    assert 0.7 < q_over_p < 6 * sin_phi / (3 - sin_phi)


def test_asymptotes_of_the_clay_model():
    model = granasym.Model("hypoplastic_clay", LONDON_CLAY)
    states = model.asymptotes(psi_epsilon_deg=[0.0, 90.0])
    ncl, csl = states.iloc[0], states.iloc[1]
    assert ncl["psi_sigma_deg"] == pytest.approx(0.0, abs=1e-6)
    assert ncl["ocr"] == pytest.approx(1.0, rel=1e-6)
    sin_phi = math.sin(math.radians(LONDON_CLAY["phi_c_deg"]))
    assert csl["q_over_p"] == pytest.approx(6 * sin_phi / (3 - sin_phi), rel=1e-6)
    assert csl["ocr"] == pytest.approx(2.0, rel=1e-6)


def test_asbs_section_at_a_void_ratio():
    model = granasym.Model("hypoplastic_clay", LONDON_CLAY)
    e = 0.9
    section = model.asbs_section(e, points=101)
    pe = model.equivalent_pressure(e)
    assert section.attrs["p_e_star_kpa"] == pytest.approx(pe)
    # p = p_e*/OCR along the section; its isotropic point lies on the NCL.
    assert np.allclose(section["p_kpa"] * section["ocr"], pe, rtol=1e-12)
    iso = section.iloc[(section["psi_sigma_deg"]).abs().argmin()]
    assert iso["p_kpa"] == pytest.approx(pe, rel=0.02)
    assert model.void_ratio_for_ocr(pe, 1.0) == pytest.approx(e, rel=1e-10)
    with pytest.raises(granasym.InputError, match="hypoplastic sand"):
        sand = granasym.Model("hypoplastic_sand", dict(
            granasym.model_parameters("hypoplastic_sand")[["parameter", "typical"]].values))
        sand.asbs_section(0.7)


def test_bad_models_raise_input_error():
    with pytest.raises(granasym.InputError, match="hypoplastic_clay"):
        granasym.Model("hypoplastic_cloy", LONDON_CLAY)
    with pytest.raises(granasym.InputError, match="lambda_star"):
        granasym.Model("hypoplastic_clay", dict(LONDON_CLAY, lambda_star=-0.1))
    with pytest.raises(granasym.InputError, match="typo"):
        granasym.Model("hypoplastic_clay", dict(LONDON_CLAY, typo=1.0))
    model = granasym.Model("hypoplastic_clay", LONDON_CLAY)
    with pytest.raises(granasym.InputError, match="psi_epsilon_deg"):
        model.element_test({"mean_stress_kpa": 100.0, "psi_sigma_deg": 0.0, "ocr": 1.0},
                           [{"type": "proportional", "stretching_rate": 1.0}])
