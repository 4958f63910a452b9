"""python/src/py_convert.cpp: thread counts, numbers and paths from Python values."""

import pathlib

import numpy as np
import pytest

import pkmopt
from conftest import source


@pytest.mark.parametrize("threads", [0, -1, 513, 1.5, True, "2", 10**30])
def test_thread_counts_outside_1_to_512_are_refused(hexapod, threads):
    with pytest.raises(pkmopt.InputError, match=r"^threads: expected an integer 1..512 or None, "
                                                r"found "):
        hexapod.analyze(np.zeros((1, 3)), threads=threads)
    with pytest.raises(pkmopt.InputError, match=r"^threads: expected an integer 1..512"):
        pkmopt.optimize("zdt1", {"algorithm": "nsga2"}, threads=threads)


def test_thread_counts_in_range_are_taken(hexapod):
    for threads in (1, np.int64(2).item(), 512):
        hexapod.analyze(np.array([[0.0, 0.0, 0.9]]), threads=threads)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), "x", None, [1.0]])
def test_numbers_must_be_finite(hexapod, value):
    with pytest.raises(pkmopt.InputError, match=r"wrench\[3\]: expected a finite number, found"):
        hexapod.analyze(np.zeros((1, 3)), wrench=[0, 0, 0, value, 0, 0])


def test_wrenches_are_six_numbers(hexapod):
    for wrench in ({1: 2}, "abcdef", [0] * 5, 3.0):
        with pytest.raises(pkmopt.InputError, match=r"^wrench: expected 6 numbers"):
            hexapod.analyze(np.zeros((1, 3)), wrench=wrench)


def test_paths_may_be_text_or_path_like():
    a = pkmopt.load_machine(source("examples", "hexapod.yaml"))
    b = pkmopt.load_machine(pathlib.Path(source("examples", "hexapod.yaml")))
    assert a.describe() == b.describe()
    with pytest.raises(TypeError):
        pkmopt.load_machine(None)


def test_problem_counts_are_integers():
    class Bad:
        bounds = ([0.0], [1.0])
        n_obj = 2.5

        def fitness(self, x):
            return [0.0, 0.0]

    with pytest.raises(pkmopt.InputError, match=r"problem.n_obj: expected an integer 0..1000000, "
                                                r"found 2.5"):
        pkmopt.optimize(Bad(), {"algorithm": "nsga2"})
    with pytest.raises(pkmopt.InputError, match=r"problem.objectives: expected an integer"):
        pkmopt.optimize({"name": "dtlz2", "objectives": -3}, {"algorithm": "nsga2"})


def test_a_path_that_is_not_utf8_raises_input_error():
    # A lone surrogate raised pybind11's RuntimeError.
    with pytest.raises(pkmopt.InputError, match="expected a path as UTF-8 text"):
        pkmopt.load_machine("machine\udc80.yaml")



def test_a_message_is_one_line_whatever_was_passed():
    # The repr of a numpy array spans lines; a message quoting it was several lines long.
    machine = pkmopt.load_machine(source("examples/hexapod.yaml"))
    for call in (lambda: machine.ik(np.zeros((2, 6), dtype=complex)),
                 lambda: machine.analyze(np.zeros((1, 6)), threads=np.zeros((4, 12))[:, ::2]),
                 lambda: machine.fk(np.zeros((50, 50)))):
        with pytest.raises((pkmopt.InputError, TypeError)) as error:
            call()
        message = str(error.value)
        assert "\n" not in message, message
        assert len(message) < 400, message


def test_text_with_a_lone_surrogate_raises_input_error():
    # pkmopt.optimize("\udcff", ...) raised pybind11's RuntimeError ("Unable to cast Python
    # instance to C++ type"); every str the module reads is UTF-8 text or an InputError.
    calls = (lambda: pkmopt.optimize("\udcff", {"algorithm": "nsga2"}),
             lambda: pkmopt.optimize({"name": "\udcff"}, {"algorithm": "nsga2"}),
             lambda: pkmopt.machine_from_dict({"model": "\udcff"}),
             lambda: pkmopt.machine_from_dict({"\udcff": 1}))
    for call in calls:
        with pytest.raises(pkmopt.InputError, match="expected UTF-8 text"):
            call()
