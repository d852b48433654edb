"""The Python front end of the workflows (shellspace/workflows/): geodesic,
log, mean and pca on procedural plates. A solve that misses its criterion
raises NotConvergedError (never InputError) naming the workflow's solve,
with the result attached; the summaries are made from the workflow's
result (the energy split once, with the path's E_K).
"""
import numpy as np
import pytest

import shellspace


def plate(n=5):
    """An n x n grid on the unit square, two triangles per cell."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    V = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1)
    F = []
    for r in range(n - 1):
        for c in range(n - 1):
            a = r * n + c
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return V, np.array(F, dtype=np.int64)


V, F = plate()


def bent(k):
    S = V.copy()
    S[:, 2] = 0.3 * k * (S[:, 0] - 0.5) ** 2
    return S


SHAPES = [bent(k) for k in range(4)]

# Each workflow with one iteration: (call, the solve its failure names).
UNCONVERGED = {
    "geodesic": (lambda **k: shellspace.geodesic(V, bent(3), F, steps=4, **k),
                 "geodesic: |grad| "),
    "log": (lambda **k: shellspace.log(V, bent(3), F, steps=4, **k),
            "log: the geodesic: |grad| "),
    "mean": (lambda **k: shellspace.mean(SHAPES, F, **k),
             "elastic mean: |grad| "),
    "pca": (lambda **k: shellspace.pca(SHAPES, F, modes=1, **k),
            "the elastic mean: |grad| "),
}


@pytest.mark.parametrize("name", sorted(UNCONVERGED))
def test_an_unconverged_workflow_raises_not_converged(name):
    call, failure = UNCONVERGED[name]
    with pytest.raises(shellspace.NotConvergedError) as error:
        call(max_iterations=1, quiet=True)
    assert not isinstance(error.value, shellspace.InputError)
    assert len(error.value.failures) == 1
    assert error.value.failures[0].startswith(failure), error.value.failures
    assert "\n" not in str(error.value)
    result, summary = error.value.result
    assert summary is error.value.summary
    assert summary["partial"] is False
    # allow_unconverged returns the same result.
    again, again_summary = call(max_iterations=1, quiet=True,
                                allow_unconverged=True)
    if isinstance(result, dict):
        assert sorted(again) == sorted(result)
    else:
        assert np.array_equal(again, result)


def test_the_geodesic_summary_is_the_workflow_result():
    path, summary = shellspace.geodesic(V, bent(3), F, steps=4, quiet=True)
    assert summary["converged"] is True
    split = summary["energy_split"]
    # The split of E_K, computed once from the path it returns.
    assert split["membrane"] + split["bending"] == pytest.approx(
        summary["path_energy"], rel=1e-12)
    assert split["bending"] > 0
    steps = len(path) - 1
    assert steps == 4
    assert summary["path_energy"] == pytest.approx(
        steps * sum(summary["step_energies"]), rel=1e-12)
    # The log of the same geodesic: K (s_1 - s_0).
    log, log_summary = shellspace.log(V, bent(3), F, steps=4, quiet=True)
    assert np.allclose(log, steps * (path[1] - path[0]), atol=1e-14, rtol=0)
    assert log_summary["log_max_norm"] == np.abs(log).max()
    assert log_summary["path_energy"] == summary["path_energy"]


def test_pca_names_its_shapes_and_stops_with_the_phase():
    shapes, summary = shellspace.pca(SHAPES, F, modes=1, quiet=True)
    assert sorted(shapes) == ["mean", "mode_1_minus", "mode_1_plus"]
    assert summary["modes"] == 1
    assert summary["failed_mode_shapes"] == []
    assert "stopped_in" not in summary
    mean, mean_summary = shellspace.mean(SHAPES, F, quiet=True)
    assert np.array_equal(mean, shapes["mean"])
    # A time limit that has passed before the first poll: the mean's phase.
    with pytest.raises(shellspace.NotConvergedError) as error:
        shellspace.pca(SHAPES, F, modes=1, quiet=True, time_limit=1e-9)
    stopped, stopped_summary = error.value.result
    assert sorted(stopped) == ["mean"]
    assert stopped_summary["stopped_in"] == "mean"
    assert stopped_summary["modes"] == 0
    assert stopped_summary["partial"] is True
