"""The Python front end of the workflows (shellspace/workflows/): geodesic,
log, mean and pca on procedural plates. A solve that misses its criterion
raises NotConvergedError (never InputError) naming the workflow's solve,
with the result attached; the summaries are made from the workflow's
result (the energy split once, with the path's E_K).
"""
import numpy as np
import pytest

import shellspace
from procedural import plate


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


# ---- The result classes (python/module_results.h) ----------------------

def test_a_geodesic_result_carries_its_numbers_as_attributes():
    result = shellspace.geodesic(V, bent(2), F, steps=4, quiet=True)
    assert isinstance(result, shellspace.GeodesicResult)
    path, summary = result  # the pair of the earlier functions
    assert path is result.path and summary is result.summary
    assert result[0] is path and result[-1] is summary and len(result) == 2
    with pytest.raises(IndexError):
        result[2]
    assert path.shape == (5, len(V), 3)
    # The attributes are the workflow's numbers: the summary's to the bit.
    assert result.path_energy == summary["path_energy"]
    assert result.iterations == summary["iterations"]
    assert result.converged and summary["converged"]
    assert result.status.name == "converged" and result.status.failures == []
    split = result.energy_split
    assert split.membrane == summary["energy_split"]["membrane"]
    assert split.bending == summary["energy_split"]["bending"]
    assert split.to_dict() == summary["energy_split"]
    # Independent: E_K = K sum_k W[s_k-1, s_k] = membrane + bending.
    assert len(result.step_energies) == 4
    assert np.isclose(4 * sum(result.step_energies), result.path_energy,
                      rtol=1e-12, atol=0)
    assert np.isclose(split.total, result.path_energy, rtol=1e-12, atol=0)
    assert result.material.mu == summary["material"]["mu"]
    assert result.material.bending == "discrete-shells"
    assert result.to_dict() == summary and result.to_dict() is not summary
    # A deep copy: writing into its nested dicts changes nothing else.
    copied = result.to_dict()
    copied["material"]["mu"] = -1.0
    assert summary["material"]["mu"] == result.material.mu != -1.0
    assert repr(result).startswith("GeodesicResult(status='converged', "
                                   "path_energy=")


def test_an_unconverged_result_names_its_status():
    with pytest.raises(shellspace.NotConvergedError) as error:
        shellspace.geodesic(V, bent(3), F, steps=4, max_iterations=1,
                            quiet=True)
    result = error.value.result
    assert isinstance(result, shellspace.GeodesicResult)
    assert not result.converged
    assert result.status.name == "not converged"
    assert result.status.failures == error.value.failures
    assert "status='not converged'" in repr(result)


def test_the_other_results_carry_their_values():
    log = shellspace.log(V, bent(2), F, steps=4, quiet=True)
    geodesic = shellspace.geodesic(V, bent(2), F, steps=4, quiet=True)
    assert isinstance(log, shellspace.LogResult)
    # LOG_K = K (s_1 - s_0) of the same geodesic.
    assert np.allclose(log.log, 4 * (geodesic.path[1] - geodesic.path[0]),
                       rtol=0, atol=1e-12)
    assert log.log_max_norm == np.abs(log.log).max()
    assert log.path_energy == geodesic.path_energy
    mean = shellspace.mean(SHAPES, F, quiet=True)
    assert isinstance(mean, shellspace.MeanResult)
    assert mean.mean is mean[0] and len(mean.energies) == len(SHAPES)
    assert np.isclose(sum(mean.energies), mean.energy, rtol=1e-12, atol=0)
    assert np.isclose(mean.energy_split.total, mean.energy, rtol=1e-12,
                      atol=0)
    pca = shellspace.pca(SHAPES, F, modes=1, quiet=True)
    assert isinstance(pca, shellspace.PcaResult)
    assert set(pca.shapes) >= {"mean", "mode_1_minus", "mode_1_plus"}
    assert np.array_equal(pca.mean, pca.shapes["mean"])
    assert pca.eigenvalues == sorted(pca.eigenvalues, reverse=True)
    assert pca.eigenvalues[0] == pca.summary["eigenvalues"][0]


def test_a_result_pickles_as_its_pair():
    import pickle
    result = shellspace.geodesic(V, bent(1), F, steps=2, quiet=True)
    path, summary = pickle.loads(pickle.dumps(result))
    assert np.array_equal(path, result.path) and summary == result.summary
