"""python/src/py_yaml.cpp: Python data read with the strict readers of machine and study files."""

import numpy as np
import pytest

import pkmopt
from conftest import source

HEXAPOD = {
    "model": "hexapod",
    "base": {"radius": 0.60, "pair_separation_deg": 20},
    "platform": {"radius": 0.25, "pair_separation_deg": 20},
    "legs": {"min_length": 0.70, "max_length": 1.15, "E": 2.1e11, "area": 3.0e-4,
             "actuator_stiffness": 2.0e8},
    "joints": {"base_max_angle_deg": 45, "platform_max_angle_deg": 45},
    "tool": {"tcp": [0, 0, -0.10]},
}


def poses():
    rng = np.random.default_rng(3)
    n = 200
    return np.column_stack([rng.uniform(-0.2, 0.2, n), rng.uniform(-0.2, 0.2, n),
                            rng.uniform(0.7, 1.0, n), rng.uniform(-15, 15, (n, 3))])


def test_a_dict_gives_the_machine_of_the_file():
    from_file = pkmopt.load_machine(source("examples", "hexapod.yaml")).analyze(poses())
    from_dict = pkmopt.machine_from_dict(HEXAPOD).analyze(poses())
    assert from_file.keys() == from_dict.keys()
    for key in from_file:
        np.testing.assert_array_equal(from_file[key], from_dict[key], err_msg=key)


def test_numpy_values_tuples_and_integers_are_read_as_numbers():
    d = dict(HEXAPOD)
    d["tool"] = {"tcp": np.array([0.0, 0.0, -0.10])}
    d["legs"] = dict(HEXAPOD["legs"], min_length=np.float64(0.70), max_length=1.15)
    d["joints"] = {"base_max_angle_deg": np.int64(45), "platform_max_angle_deg": 45}
    d["platform"] = {"radius": 0.25, "pair_separation_deg": 20}
    m = pkmopt.machine_from_dict(d)
    a = m.analyze(poses())
    b = pkmopt.machine_from_dict(HEXAPOD).analyze(poses())
    np.testing.assert_array_equal(a["tau"], b["tau"])


def test_floats_keep_every_digit():
    d = dict(HEXAPOD)
    d["legs"] = dict(HEXAPOD["legs"], area=0.1 + 0.2)  # 0.30000000000000004
    a = pkmopt.machine_from_dict(d).analyze(poses(), wrench=[0, 0, -1000, 0, 0, 0])
    d["legs"] = dict(HEXAPOD["legs"], area=0.3)
    b = pkmopt.machine_from_dict(d).analyze(poses(), wrench=[0, 0, -1000, 0, 0, 0])
    assert not np.array_equal(a["stiffness_min"], b["stiffness_min"])


def test_unknown_keys_get_the_message_of_a_file(tmp_path):
    d = dict(HEXAPOD, legz={"a": 1})
    with pytest.raises(pkmopt.InputError) as error:
        pkmopt.machine_from_dict(d)
    message = str(error.value)
    assert message.startswith("<dict>: legz: ")
    # The same text as the file's, after the file's location.
    import json
    path = tmp_path / "m.yaml"
    path.write_text(json.dumps(d))
    with pytest.raises(pkmopt.InputError) as from_file:
        pkmopt.load_machine(path)
    file_message = str(from_file.value)
    assert file_message.endswith(message[len("<dict>: "):])


def test_bad_values_name_the_key():
    d = dict(HEXAPOD, legs=dict(HEXAPOD["legs"], min_length="short"))
    with pytest.raises(pkmopt.InputError, match=r"^<dict>: legs.min_length: expected .*'short'"):
        pkmopt.machine_from_dict(d)
    d = dict(HEXAPOD, legs=dict(HEXAPOD["legs"], min_length=float("nan")))
    with pytest.raises(pkmopt.InputError, match=r"legs.min_length: expected a finite number"):
        pkmopt.machine_from_dict(d)


def test_values_that_are_not_data_are_refused():
    with pytest.raises(pkmopt.InputError, match=r"tool.tcp\[0\]: expected a dict, list, text, "
                                                r"number, bool or None, found a object"):
        pkmopt.machine_from_dict(dict(HEXAPOD, tool={"tcp": [object(), 0, 0]}))
    with pytest.raises(pkmopt.InputError, match=r"base: expected text keys, found the key 1"):
        pkmopt.machine_from_dict(dict(HEXAPOD, base={1: 0.6}))
    with pytest.raises(pkmopt.InputError, match=r"machine_from_dict: expected a dict, found a list"):
        pkmopt.machine_from_dict([1, 2])
    deep = {}
    inner = deep
    for _ in range(100):
        inner["a"] = {}
        inner = inner["a"]
    with pytest.raises(pkmopt.InputError, match=r"nested at most 64 levels"):
        pkmopt.machine_from_dict(dict(HEXAPOD, tool=deep))


def test_input_error_is_a_value_error():
    assert issubclass(pkmopt.InputError, ValueError)
