"""python/src/py_study.cpp: run_study, read_front and calibrate against `pkmopt run` and
`pkmopt calibrate`."""

import json
import os
import signal

import numpy as np
import pytest

import pkmopt
from conftest import run_cli, source

# A small hexapod study (hexapod-quick with a shorter run), as a dict; as JSON text it is also a
# study file the command line reads (JSON is YAML).
STUDY = {
    "study": "python-quick",
    "description": "stiffness vs machine size",
    "machine": {
        "model": "hexapod",
        "parameters": {
            "base_radius": {"min": 0.45, "max": 0.75},
            "platform_radius": {"min": 0.18, "max": 0.30},
            "base_pair_separation_deg": 20,
            "platform_pair_separation_deg": {"min": 10, "max": 40},
            "min_length": {"min": 0.55, "max": 0.90},
            "stroke": {"min": 0.35, "max": 0.70},
            "home_height": 0.0,
        },
        "legs": {"E": 2.1e11, "area": 3.0e-4, "actuator_stiffness": 2.0e8},
        "joints": {"base_max_angle_deg": 45, "platform_max_angle_deg": 45},
        "tool": {"tcp": [0, 0, -0.10]},
    },
    "task": {
        "region": {"shape": "box", "centre": [0, 0, 0.90], "size": [0.30, 0.30, 0.20],
                   "points": [2, 2, 2]},
        "wrench": [300, 300, -3000, 0, 0, 0],
    },
    "objectives": [{"maximize": "stiffness_min"}, {"minimize": "machine_size"}],
    "constraints": ["task_reachable", {"metric": "leg_force_max", "max": 10500}],
    "optimizer": {"algorithm": "nsga2", "population": 16, "generations": 6, "seed": 3},
    "output": {"designs": True},
}

SAME_FILES = ["pareto.csv", "pareto.json", "evaluations.csv", "journal.txt"]


def cli_run(tmp_path, study=STUDY):
    path = tmp_path / "study.yaml"
    path.write_text(json.dumps(study))
    out = tmp_path / "cli"
    run_cli("run", str(path), "--out", str(out), "--no-progress")
    return out


def test_a_dict_study_gives_the_files_of_the_cli(tmp_path):
    cli = cli_run(tmp_path)
    front = pkmopt.run_study(STUDY, out=tmp_path / "py")
    for name in SAME_FILES:
        assert (tmp_path / "py" / name).read_bytes() == (cli / name).read_bytes(), name
    run = front["run"]
    assert run["design_study"] and run["status"] == "ok"
    assert run["designs"] == len(front["ids"]) > 0
    assert run["evaluations"] == 16 * 7


def test_read_front_gives_the_front_in_user_units(tmp_path):
    cli = cli_run(tmp_path)
    front = pkmopt.read_front(cli)
    assert front["study"] == "python-quick" and front["model"] == "hexapod"
    names = [o["name"] for o in front["objective_info"]]
    senses = [o["sense"] for o in front["objective_info"]]
    assert names == ["stiffness_min", "machine_size"] and senses == ["maximize", "minimize"]
    n = len(front["ids"])
    assert front["objectives"].shape == (n, 2)
    assert front["parameters"].shape == (n, len(front["parameter_info"]))
    # The objectives are pareto.csv's columns (user sign: stiffness positive, N/m).
    np.testing.assert_array_equal(front["objectives"][:, 0], front["columns"]["stiffness_min"])
    assert np.all(front["objectives"][:, 0] > 0)
    assert front["columns"]["id"] == front["ids"]
    assert front["knee"] in front["ids"]
    # The knee's machine file loads; its stiffness over the task's poses (x, y +-0.15 m,
    # z 0.80..1.00 m about home_height 0, no tilt) is the worst the front reports.
    k = front["ids"].index(front["knee"])
    machine = pkmopt.load_machine(front["machine_files"][k])
    assert machine.model == "hexapod"
    corners = np.array([[x, y, z] for x in (-0.15, 0.15) for y in (-0.15, 0.15)
                        for z in (0.80, 1.00)])
    r = machine.analyze(corners, wrench=[300, 300, -3000, 0, 0, 0])
    assert r["reachable"].all()
    assert np.min(r["stiffness_min"]) == pytest.approx(front["objectives"][k, 0], rel=1e-9)
    assert front["summary"]["points"] == n and front["summary"]["knee"] == front["knee"]
    with pytest.raises(pkmopt.InputError, match=r"expected pareto.csv"):
        pkmopt.read_front(tmp_path)


def test_read_front_gives_text_columns_as_text(tmp_path):
    # The failure column (always empty on a front) came back as an array of NaN.
    front = pkmopt.read_front(cli_run(tmp_path))
    n = len(front["ids"])
    assert front["columns"]["failure"] == [""] * n
    assert isinstance(front["columns"]["feasible"], np.ndarray)


def test_read_front_masks_what_the_files_hold_as_null_and_returns_no_nan(tmp_path):
    # pareto.json holds null for a value that is not finite (an unbounded constrained metric at
    # a singular pose, a damaged file) and pareto.csv an empty cell; read_front gave NaN there.
    out = cli_run(tmp_path)
    doc = json.loads((out / "pareto.json").read_text())
    first = doc["designs"][0]
    first["objectives"]["machine_size"] = None
    constraint = doc["constraints"][0]["name"]
    first["constraints"][constraint] = None
    (out / "pareto.json").write_text(json.dumps(doc))
    lines = (out / "pareto.csv").read_text().splitlines()
    header = lines[0].split(",")
    cells = lines[1].split(",")
    cells[header.index("stiffness_min")] = ""
    lines[1] = ",".join(cells)
    (out / "pareto.csv").write_text("\n".join(lines) + "\n")

    front = pkmopt.read_front(out)
    n = len(front["ids"])
    arrays = [front["objectives"], front["constraints"], front["parameters"],
              front["home_height"], front["columns"]["stiffness_min"]]
    for a in arrays:
        assert np.ma.isMaskedArray(a)
        assert not np.any(np.isnan(a.compressed()))
    assert front["objectives"].mask[0, 1] and front["objectives"].mask.sum() == 1
    assert front["constraints"].mask[0, 0] and front["constraints"].mask.sum() == 1
    assert not np.any(front["parameters"].mask)
    assert front["columns"]["stiffness_min"].mask.tolist() == [True] + [False] * (n - 1)
    # Statistics leave the missing value out, as numpy.ma does.
    assert front["objectives"][:, 1].count() == n - 1
    assert np.isfinite(front["objectives"][:, 1].min())


def test_a_study_file_runs_from_its_path(tmp_path):
    front = pkmopt.run_study(source("studies", "library", "zdt1-nsga2.yaml"), out=tmp_path / "z")
    assert front["run"]["design_study"] is False
    f1, f2 = front["columns"]["f_1"], front["columns"]["f_2"]
    assert len(f1) > 50
    # ZDT1's front is f2 = 1 - sqrt(f1) (g = 1); NSGA-II gets close to it.
    assert np.max(f2 - (1 - np.sqrt(f1))) < 0.05
    run_cli("run", source("studies", "library", "zdt1-nsga2.yaml"), "--out", str(tmp_path / "c"),
            "--no-progress")
    assert (tmp_path / "z" / "pareto.csv").read_bytes() == \
        (tmp_path / "c" / "pareto.csv").read_bytes()


def test_progress_is_reported_after_every_batch(tmp_path):
    seen = []
    pkmopt.run_study(STUDY, out=tmp_path / "p", progress=seen.append)
    assert len(seen) == 7  # the initial population and 6 generations
    assert [p["requests"] for p in seen] == [16 * (k + 1) for k in range(7)]
    assert all(p["expected_requests"] == 16 * 7 for p in seen)


def test_ctrl_c_stops_the_run_and_resume_finishes_it(tmp_path):
    out = tmp_path / "k"
    batches = []

    def interrupt_after_three(p):
        batches.append(p["requests"])
        if len(batches) == 3:
            os.kill(os.getpid(), signal.SIGINT)  # what Ctrl-C does

    with pytest.raises(KeyboardInterrupt):
        pkmopt.run_study(STUDY, out=out, progress=interrupt_after_three)
    # The journal holds the three batches evaluated before the interrupt was seen.
    journal = (out / "journal.txt").read_text().splitlines()
    assert 3 * 16 <= len(journal) - 1 <= 4 * 16
    assert not (out / "pareto.csv").exists()
    with pytest.raises(pkmopt.InputError, match=r"holds a previous run"):
        pkmopt.run_study(STUDY, out=out)
    front = pkmopt.run_study(STUDY, out=out, resume=True)
    assert front["run"]["resumed"] and front["run"]["from_cache"] >= 3 * 16 - 16
    cli = cli_run(tmp_path)
    for name in ["pareto.csv", "pareto.json"]:
        assert (out / name).read_bytes() == (cli / name).read_bytes(), name


def test_an_exception_in_progress_stops_the_run(tmp_path):
    def fail(_):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        pkmopt.run_study(STUDY, out=tmp_path / "e", progress=fail)


def test_bad_studies_raise_input_error_with_the_key(tmp_path):
    bad = json.loads(json.dumps(STUDY))
    bad["optimizer"]["population"] = "many"
    with pytest.raises(pkmopt.InputError, match=r"^<dict>: optimizer.population: expected"):
        pkmopt.run_study(bad, out=tmp_path / "b")
    assert not (tmp_path / "b" / "journal.txt").exists()
    with pytest.raises(pkmopt.InputError, match=r"threads: expected an integer 1..512"):
        pkmopt.run_study(STUDY, out=tmp_path / "t", threads=-1)


def test_calibrate_gives_the_report_of_the_cli(tmp_path):
    path = source("studies", "library", "calibration-demo", "calibration.yaml")
    report = pkmopt.calibrate(path, out=tmp_path / "py")
    run_cli("calibrate", path, "--out", str(tmp_path / "cli"))
    cli = json.loads((tmp_path / "cli" / "report.json").read_text())
    for key in cli:
        assert report[key] == cli[key], key
    for name in ["report.json", "report.txt", "calibrated.yaml"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert report["calibrated_machine_yaml"] == (tmp_path / "cli" / "calibrated.yaml").read_text()
    with pytest.raises(pkmopt.InputError, match=r"cannot open"):
        pkmopt.calibrate(tmp_path / "missing.yaml")
