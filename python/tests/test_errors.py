# SPDX-License-Identifier: Apache-2.0
# Bad input raises a clear exception: ValueError with the one-line message the CLI prints for the same mistake
# (after "shadecore: error: "), TypeError for a wrong dtype; nothing is computed on a silently changed input.
import threading
import time

import numpy as np
import pytest

import shadecore


def raises(exc, fn, *args, **kw):
    with pytest.raises(exc) as e:
        fn(*args, **kw)
    msg = str(e.value)
    assert "\n" not in msg and msg, msg
    return msg


@pytest.mark.parametrize("cli_args,call", [
    (["eval", "--variant", "nope", "--n", 16, "--code", 0], lambda: shadecore.eval_unit("nope", [0], 16)),
    (["eval", "--config", "huge", "--n", 16, "--code", 0], lambda: shadecore.cs16([0], 16, config="huge")),
    (["eval", "--n", 15, "--code", 0], lambda: shadecore.cs16([0], 15)),
    (["eval", "--n", 1025, "--code", 0], lambda: shadecore.schlick_nr([0, 1], [16, 1025])),
    (["eval", "--frac", 30, "--n", 16, "--code", 0], lambda: shadecore.cs16([0], 16, frac=30)),
    (["eval", "--frac", 24, "--guard", 8, "--n", 16, "--code", 0], lambda: shadecore.cs16([0], 16, frac=24, guard=8)),
    (["eval", "--cutoff", "round", "--n", 16, "--code", 0], lambda: shadecore.cs16([0], 16, cutoff="round")),
    (["eval", "--norm", "lambert", "--n", 16, "--code", 0], lambda: shadecore.cs16([0], 16, norm="lambert")),
    (["eval", "--norm", "phong", "--coef", "exact", "--n", 16, "--code", 0],
     lambda: shadecore.cs16([0], 16, norm="phong", coef="exact")),
    (["sweep", "--variant", "nope"], lambda: shadecore.sweep("nope")),
    (["sweep", "--n", "16...x"], lambda: shadecore.sweep("cs16", "16...x")),
    (["sweep", "--n", "64..16"], lambda: shadecore.sweep("cs16", "64..16")),
])
def test_same_message_as_cli(cli, cli_args, call):
    assert raises(ValueError, call) == cli.error(*cli_args)


def test_code_and_cos_range_messages_match_cli(cli):
    assert "--" + raises(ValueError, shadecore.cs16, [0, 200000], 16) == cli.error("eval", "--n", 16, "--code", 200000)
    assert "--" + raises(ValueError, shadecore.cs16, cos=[3.0], n=16) == cli.error("eval", "--n", 16, "--cos", 3)
    assert "--" + raises(ValueError, shadecore.cs16, [-600], 16, config="narrow") == \
        cli.error("eval", "--config", "narrow", "--n", 16, "--code", -600)


def test_options_a_unit_does_not_take():
    assert "cutoff applies to cs16 and its forms only" in raises(ValueError, shadecore.schlick_nr, [0], 16,
                                                                 cutoff="sign_clamp")
    assert "guard applies to cs16 and its forms only" in raises(ValueError, shadecore.table256, [0], 16, guard=5)
    assert "coef needs norm=MODEL" in raises(ValueError, shadecore.cs16, [0], 16, coef="classical")
    assert "cutoff and guard apply to cs16" in raises(ValueError, shadecore.sweep, "schlick_div", "16", guard=5)


def test_wrong_types_and_shapes():
    assert "codes must be integers" in raises(TypeError, shadecore.cs16, np.array([0.5]), 16)
    assert "n must be integers" in raises(TypeError, shadecore.cs16, [0], 16.0)
    assert "exactly one of codes and cos=" in raises(TypeError, shadecore.cs16, [0], 16, cos=[0.5])
    assert "n is required" in raises(TypeError, shadecore.cs16, [0])
    assert "n has 2 elements for 3 inputs" in raises(ValueError, shadecore._core.unit_eval, "cs16",
                                                     np.zeros(3, np.int64), np.array([16, 17]))
    raises(ValueError, shadecore.cs16, np.zeros(3, np.int64), np.array([16, 17]))  # numpy: cannot broadcast
    assert "last axis of length 3" in raises(ValueError, shadecore.normalize3, np.zeros((4, 2), np.int64))
    assert "out of range" in raises(ValueError, shadecore.normalize3, [[2**31, 0, 0]])
    assert "negative" in raises(ValueError, shadecore.recip, [5, -1])
    assert "fraction width 30" in raises(ValueError, shadecore.recip, [5], frac=30)
    assert "unit output code" in raises(ValueError, shadecore.energy_eval, [70000], 5)
    assert "coefficient code" in raises(ValueError, shadecore.energy_eval, [7], -5)
    assert "unknown model" in raises(ValueError, shadecore.coef_value, "lambert", 16)
    assert "does not fit a signed 64-bit" in raises(ValueError, shadecore.cs16, np.array([2**64 - 1], np.uint64), 16)


def test_gil_released_during_array_calls():
    """While a long C++ call runs in a thread, the main thread keeps running (its longest stall is far shorter
    than the call)."""
    res = {}

    def work():
        t0 = time.perf_counter()
        shadecore.sweep("cs16", "16..1024", threads=1)
        res["t"] = time.perf_counter() - t0

    th = threading.Thread(target=work)
    th.start()
    last, gap = time.perf_counter(), 0.0
    while th.is_alive():
        now = time.perf_counter()
        gap, last = max(gap, now - last), now
    th.join()
    assert res["t"] > 0.05
    assert gap < 0.5 * res["t"], (gap, res["t"])
