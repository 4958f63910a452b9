"""python/src/py_machine.cpp: pkmopt.Machine against the command line and against physics."""

import csv
import io
import json
import math
import os
import signal
import threading
import time
import tracemalloc

import numpy as np
import pytest

import pkmopt
from conftest import cli_error, run_cli, source

WRENCH = [120.0, -300.0, -2500.0, 15.0, -20.0, 8.0]
MODELS = ["hexapod.yaml", "hexapod_legs.yaml", "hexapod_bodies.yaml", "hexapod_masses.yaml",
          "delta.yaml", "linear_delta.yaml", "hexaglide.yaml", "tripod_3prs.yaml",
          "schoenflies_4pus.yaml", "hybrid_gantry_3prs.yaml", "hybrid_long_axis_hexapod.yaml",
          "hybrid_long_axis_masses.yaml"]


def write_pose_csv(path, poses):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "y", "z", "rx", "ry", "rz"])
        for row in poses:
            w.writerow([repr(float(v)) for v in row])


def read_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[1:]


@pytest.mark.parametrize("name", MODELS)
def test_analyze_equals_the_cli_bit_for_bit(name, tmp_path):
    machine = pkmopt.load_machine(source("examples", name))
    # Poses over a tall box about the base axis (reachable and unreachable ones alike: the
    # numbers of both must agree), and the base origin.
    rng = np.random.default_rng(7)
    centre = np.zeros(6)
    poses = np.column_stack([rng.uniform(-0.1, 0.1, 300), rng.uniform(-0.1, 0.1, 300),
                             rng.uniform(-1.2, 1.2, 300), rng.uniform(-8, 8, (300, 3))])
    poses = np.vstack([poses, centre[None, :]])
    pose_file = tmp_path / "poses.csv"
    write_pose_csv(pose_file, poses)
    args = ["analyze", source("examples", name), "--poses", str(pose_file), "--wrench",
            ",".join(repr(w) for w in WRENCH)]
    with_masses = machine.natural_frequency_count > 0
    if with_masses:
        args.append("--mode-shapes")
    args.append("--compliance")
    _, out, _ = run_cli(*args)
    header, rows = read_csv(out)
    r = machine.analyze(poses, wrench=WRENCH, compliance=True, mode_shapes=with_masses)
    n = machine.num_actuators
    assert len(rows) == len(poses)
    column = {name: i for i, name in enumerate(header)}
    for i, row in enumerate(rows):
        assert (row[column["reachable"]] == "1") == bool(r["reachable"][i])
        for j in range(n):
            assert float(row[column[f"q_{j + 1}"]]) == r["q"][i, j]
            assert float(row[column[f"tau_{j + 1}"]]) == r["tau"][i, j]
        for key, value in r.items():
            if isinstance(value, np.ndarray) and value.ndim == 1 and key != "reachable":
                assert float(row[column[key]]) == value[i], key
        for a in range(6):
            for b in range(6):
                assert float(row[column[f"C_{a + 1}{b + 1}"]]) == r["compliance"][i, a, b]
        if "clearance_pair" in column:
            assert row[column["clearance_pair"]] == r["clearance_pair"][i]
        if with_masses:
            shapes = r["mode_shapes"][i]
            names = [h for h in header if h.startswith("mode_")]
            flat = [float(row[column[h]]) for h in names]
            assert flat == list(shapes.reshape(-1))
    # Every numeric CSV column is in the dict (q_j, tau_j, C_ab and mode_* grouped).
    for h in header[6:]:
        if h.startswith(("q_", "tau_", "C_", "mode_")):
            continue
        assert h in r, h


def test_poses_with_three_columns_have_zero_angles(hexapod):
    p3 = np.array([[0.0, 0.0, 0.9], [0.05, -0.02, 0.85]])
    p6 = np.hstack([p3, np.zeros((2, 3))])
    a, b = hexapod.analyze(p3), hexapod.analyze(p6)
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
    one = hexapod.analyze(np.array([0.0, 0.0, 0.9]))
    assert one["q"].shape == (1, 6)


def test_the_input_is_read_in_place(hexapod):
    n = 400_000
    poses = np.zeros((n, 6))
    poses[:, 2] = 0.9
    poses[:, 3] = np.linspace(-10, 10, n)
    hexapod.analyze(poses[:10])
    tracemalloc.start()
    r = hexapod.analyze(poses)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    outputs = sum(v.nbytes for v in r.values() if isinstance(v, np.ndarray))
    # A copy of the input would add poses.nbytes (19.2 MB) to the peak.
    assert peak < outputs + poses.nbytes / 4, (peak, outputs, poses.nbytes)


def test_any_float_array_layout_gives_the_same_numbers(hexapod):
    rng = np.random.default_rng(1)
    poses = np.column_stack([rng.uniform(-0.1, 0.1, (50, 2)), rng.uniform(0.8, 1.0, 50),
                             rng.uniform(-5, 5, (50, 3))])
    a = hexapod.analyze(poses)
    b = hexapod.analyze(np.asfortranarray(poses))
    c = hexapod.analyze(poses.tolist())
    wide = np.zeros((50, 12))
    wide[:, ::2] = poses
    d = hexapod.analyze(wide[:, ::2])
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
        np.testing.assert_array_equal(a[key], c[key])
        np.testing.assert_array_equal(a[key], d[key])


def test_out_reuses_the_arrays_of_an_earlier_call(hexapod):
    poses = np.array([[0.0, 0.0, 0.9, 0, 0, 0], [0.05, 0.0, 0.85, 5, 0, 0]])
    first = hexapod.analyze(poses, wrench=WRENCH)
    keep = {k: (v.copy() if isinstance(v, np.ndarray) else v) for k, v in first.items()}
    tau = first["tau"]
    again = hexapod.analyze(poses[::-1].copy(), wrench=WRENCH, out=first)
    assert again["tau"] is tau
    np.testing.assert_array_equal(again["tau"], keep["tau"][::-1])
    with pytest.raises(pkmopt.InputError, match=r"out\['reachable'\]: expected .* shape \(3,\)"):
        hexapod.analyze(np.vstack([poses, poses[:1]]), out=first)


def test_threads_do_not_change_the_numbers(hexapod):
    rng = np.random.default_rng(2)
    poses = np.column_stack([rng.uniform(-0.15, 0.15, (5000, 2)), rng.uniform(0.75, 0.95, 5000),
                             rng.uniform(-15, 15, (5000, 3))])
    a = hexapod.analyze(poses, wrench=WRENCH, threads=1)
    b = hexapod.analyze(poses, wrench=WRENCH, threads=2)
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])


def test_the_gil_is_released_while_analyze_runs(hexapod):
    poses = np.zeros((1_500_000, 6))
    poses[:, 2] = 0.9
    done = threading.Event()
    ticks = [0]

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    hexapod.analyze(poses, threads=1)
    seconds = time.perf_counter() - start
    done.set()
    counter.join()
    # Holding the GIL would freeze the counter for the whole call.
    assert ticks[0] > 0.03 * seconds / 0.001, (ticks[0], seconds)


def test_ctrl_c_stops_a_long_analyze(hexapod):
    poses = np.zeros((4_000_000, 6))
    poses[:, 2] = 0.9
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        hexapod.analyze(poses, threads=1)  # about 3 s to the end
    elapsed = time.perf_counter() - start
    timer.join()
    # Seen at the next chunk of 65,536 poses (about 50 ms).
    assert elapsed < 1.5, elapsed


def test_bad_poses_and_wrenches_raise_input_error(hexapod):
    with pytest.raises(pkmopt.InputError, match=r"poses\[1, 2\]: expected a finite number, "
                                                r"found nan"):
        hexapod.analyze(np.array([[0, 0, 0.9], [0, 0, np.nan]]))
    with pytest.raises(pkmopt.InputError, match=r"poses: expected shape \(N, 3\)"):
        hexapod.analyze(np.zeros((4, 5)))
    with pytest.raises(pkmopt.InputError, match=r"wrench: expected 6 numbers"):
        hexapod.analyze(np.zeros((1, 3)), wrench=[1, 2])
    with pytest.raises(pkmopt.InputError, match=r"wrench\[2\]: expected a finite number"):
        hexapod.analyze(np.zeros((1, 3)), wrench=[0, 0, math.inf, 0, 0, 0])
    with pytest.raises(pkmopt.InputError, match=r"threads: expected an integer 1..512"):
        hexapod.analyze(np.zeros((1, 3)), threads=0)
    with pytest.raises(pkmopt.InputError, match=r"mode_shapes: needs a mass model"):
        hexapod.analyze(np.zeros((1, 3)), mode_shapes=True)


def test_ik_and_fk_round_trip(hexapod):
    rng = np.random.default_rng(4)
    for _ in range(20):
        pose = np.concatenate([rng.uniform(-0.1, 0.1, 2), rng.uniform(0.8, 0.95, 1),
                               rng.uniform(-8, 8, 3)])
        ik = hexapod.ik(pose)
        assert ik["q"] is not None
        fk = hexapod.fk(ik["q"], guess=[0, 0, 0.9, 0, 0, 0])
        assert fk["converged"], fk["message"]
        np.testing.assert_allclose(fk["pose"][:3], pose[:3], atol=1e-10)
        np.testing.assert_allclose(fk["pose"][3:], pose[3:], atol=1e-8)
        assert fk["residual"] <= 1e-12
    # The CLI gives the same pose.
    q = hexapod.ik([0.01, 0.02, 0.9, 1, 2, 3])["q"]
    _, out, _ = run_cli("fk", source("examples", "hexapod.yaml"), "--q",
                        ",".join(repr(float(v)) for v in q))
    header, rows = read_csv(out)
    fk = hexapod.fk(q)
    assert [float(v) for v in rows[0][:6]] == list(fk["pose"])


def test_fk_refuses_meaningless_coordinates(hexapod):
    with pytest.raises(pkmopt.InputError, match=r"^q: expected 6 actuator coordinates"):
        hexapod.fk([1.0, 1.0])
    message = cli_error("fk", source("examples", "hexapod.yaml"), "--q", "1,1,1,1,1,-1")
    with pytest.raises(pkmopt.InputError) as error:
        hexapod.fk([1, 1, 1, 1, 1, -1])
    # The command line names its option --q.
    assert "--" + str(error.value).split(", found")[0] == message.split(", found")[0]
    with pytest.raises(pkmopt.InputError, match=r"max_iterations: expected an integer >= 1"):
        hexapod.fk([1.0] * 6, max_iterations=0)


def rotation_zyx(deg):
    rx, ry, rz = np.radians(deg)
    cx, sx, cy, sy, cz, sz = np.cos(rx), np.sin(rx), np.cos(ry), np.sin(ry), np.cos(rz), np.sin(rz)
    Rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def angles_zyx(R):
    ry = -math.asin(max(-1.0, min(1.0, R[2, 0])))
    rx = math.atan2(R[2, 1], R[2, 2])
    rz = math.atan2(R[1, 0], R[0, 0])
    return np.degrees([rx, ry, rz])


def axis_angle(w):
    theta = np.linalg.norm(w)
    if theta == 0:
        return np.eye(3)
    k = w / theta
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K


def moved(pose, twist, t):
    """The pose after moving with the TCP twist [v; omega] (base axes) for a time t."""
    R = axis_angle(np.asarray(twist[3:]) * t) @ rotation_zyx(pose[3:])
    return np.concatenate([pose[:3] + np.asarray(twist[:3]) * t, angles_zyx(R)])


@pytest.mark.parametrize("name,pose", [("hexapod.yaml", [0.03, -0.02, 0.88, 4.0, -3.0, 6.0])])
def test_jacobian_against_finite_differences_and_equilibrium(name, pose):
    machine = pkmopt.load_machine(source("examples", name))
    pose = np.array(pose)
    J = machine.jacobian(pose)
    assert J.shape == (machine.num_actuators, 6)
    h = 1e-6
    for k in range(6):
        e = np.zeros(6)
        e[k] = 1.0
        plus = machine.ik(moved(pose, e, h))["q"]
        minus = machine.ik(moved(pose, e, -h))["q"]
        np.testing.assert_allclose((plus - minus) / (2 * h), J[:, k], rtol=1e-6, atol=1e-7)
    # J^T tau = w with the forces analyze gives for that wrench.
    tau = machine.analyze(pose, wrench=WRENCH)["tau"][0]
    np.testing.assert_allclose(J.T @ tau, WRENCH, rtol=1e-9, atol=1e-7)


def test_describe_prints_what_the_cli_prints():
    for name in ["hexapod.yaml", "delta.yaml", "hybrid_gantry_3prs.yaml"]:
        machine = pkmopt.load_machine(source("examples", name))
        _, out, _ = run_cli("describe", source("examples", name))
        assert machine.describe() == out
    assert pkmopt.load_machine(source("examples", "delta.yaml")).revolute_actuators


def test_a_serial_machine_has_degrees_and_metres_per_axis():
    machine = pkmopt.load_machine(source("examples", "serial_641236.yaml"))
    assert not machine.revolute_actuators
    assert machine.revolute_axes == [True, True, False, False, False]
    # C = 30 deg, A = -20 deg, X, Y, Z in metres: fk then ik gives them back in the same units.
    pose = machine.fk([30.0, -20.0, 0.1, 0.05, 0.2])["pose"]
    np.testing.assert_allclose(machine.ik(pose)["q"], [30.0, -20.0, 0.1, 0.05, 0.2], atol=1e-9)
    _, out, _ = run_cli("fk", source("examples", "serial_641236.yaml"), "--q", "30,-20,0.1,0.05,0.2")
    row = out.splitlines()[1].split(",")
    np.testing.assert_allclose(pose, [float(v) for v in row[:6]], rtol=1e-12, atol=1e-12)


def test_load_errors_carry_the_cli_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("model: hexapod\nbase: {radius: 0.6, pair_separation_deg: 20}\n"
                   "platform: {radius: 0.25, pair_separation_deg: 20}\n"
                   "legs: {min_length: abc, max_length: 1.15, axial_stiffness: 1e8}\n")
    message = cli_error("analyze", str(bad), "--poses", str(bad))
    with pytest.raises(pkmopt.InputError) as error:
        pkmopt.load_machine(bad)
    assert str(error.value) == message
    with pytest.raises(pkmopt.InputError, match=r"cannot open"):
        pkmopt.load_machine(tmp_path / "missing.yaml")


def test_workspace_matches_the_cli(tmp_path):
    machine = pkmopt.load_machine(source("examples", "hexapod.yaml"))
    ws = machine.workspace(resolution=0.04, points=True)
    run_cli("workspace", source("examples", "hexapod.yaml"), "--resolution", "0.04", "--out",
            str(tmp_path))
    summary = json.loads((tmp_path / "summary.json").read_text())
    for key in ["volume", "convex_hull_volume", "global_conditioning_index", "stiffness_min_min",
                "inside_nodes", "boundary_vertices", "boundary_triangles", "grid_nodes"]:
        assert ws[key] == summary[key], key
    assert ws["vertices"].shape == (summary["boundary_vertices"], 3)
    assert ws["faces"].shape == (summary["boundary_triangles"], 3)
    # The mesh encloses the reported volume (divergence theorem).
    v, f = ws["vertices"], ws["faces"]
    volume = np.sum(np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]]))) / 6
    assert volume == pytest.approx(ws["surface_volume"], rel=1e-9)
    assert ws["points"]["position"].shape[0] == summary["inside_nodes"]
    with pytest.raises(pkmopt.InputError, match=r"tilt_deg: expected an angle"):
        machine.workspace(tilt_deg=-1)
    with pytest.raises(pkmopt.InputError, match=r"mode: expected 'all' or 'some'"):
        machine.workspace(mode="any")


def test_a_machine_not_made_by_load_machine_raises_instead_of_crashing():
    # Machine.__new__(Machine) once made an object without its C++ machine: analyze() or .model
    # on it crashed the interpreter (a segmentation fault).
    for make in (lambda: pkmopt.Machine.__new__(pkmopt.Machine), lambda: pkmopt.Machine()):
        with pytest.raises(TypeError, match="pkmopt.load_machine"):
            make()
    assert pkmopt.load_machine(source("examples/hexapod.yaml")).model == "hexapod"



def test_lengths_beyond_a_kilometre_and_numbers_that_underflow_raise_input_error(hexapod):
    # analyze at x = 1e308 once gave inf in tau, q and more; the CLI's number policy holds here too.
    for bad, message in ((1e308, r"a finite number within \+-1e15"), (1e4, r"a length within \+-1000 m"),
                         (1e-310, r".*at least 1e-30 in magnitude")):
        with pytest.raises(pkmopt.InputError, match=r"poses\[0, 0\]: expected " + message):
            hexapod.analyze(np.array([[bad, 0, 0.9, 0, 0, 0]]))
    with pytest.raises(pkmopt.InputError, match=r"poses\[0, 5\]: expected .*within \+-1e15"):
        hexapod.analyze(np.array([[0, 0, 0.9, 0, 0, 1e20]]))
    with pytest.raises(pkmopt.InputError, match=r"pose\[2\]: expected a length within \+-1000 m"):
        hexapod.ik([0, 0, 2e3])
    with pytest.raises(pkmopt.InputError, match=r"q\[0\]: expected a length within \+-1000 m"):
        hexapod.fk([1e4, 1, 1, 1, 1, 1])
    with pytest.raises(pkmopt.InputError, match=r"wrench\[0\]: expected a force or moment"):
        hexapod.analyze(np.zeros((1, 3)), wrench=[1e12, 0, 0, 0, 0, 0])
    with pytest.raises(pkmopt.InputError, match=r"resolution: expected a length within"):
        hexapod.workspace(resolution=2e3)
    assert hexapod.analyze(np.array([[0, 0, 0.9, 0, 0, 0]]))["reachable"][0]


def test_inf_only_in_the_documented_arrays_at_a_singular_pose():
    # docs/conventions.md ("Singular poses") lists the outputs that can be inf: tau, tcp_error_max,
    # tcp_deflection, tcp_rotation_deflection_deg and the compliance; nothing is ever NaN.
    machine = pkmopt.load_machine(source("examples/hexapod_masses.yaml"))
    result = machine.analyze(np.array([[0, 0, 0.9, 0, 0, 90], [0, 0, 0.9, 0, 0, 0]]),
                             wrench=[100, -200, -1000, 5, -5, 10], compliance=True,
                             mode_shapes=True)
    documented = {"tau", "tcp_error_max", "tcp_deflection", "tcp_rotation_deflection_deg",
                  "compliance"}
    infinite = set()
    for name, values in result.items():
        values = np.asarray(values)
        if values.dtype.kind != "f":
            continue
        assert not np.isnan(values).any(), name
        if np.isinf(values).any():
            infinite.add(name)
        assert np.isfinite(values[1]).all(), name  # the level pose is not singular
    assert infinite == documented
