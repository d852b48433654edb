"""Tests of the Python module `shellspace` (python/shellspace_module.cc and python/module_*.cc).

Run by CTest (`python_tests`) with PYTHONPATH at the build tree's python/
folder, SHELLSPACE_CLI the built `shellspace` tool and SHELLSPACE_DATA the
shared meshes. Values are checked against independent expectations: W[S, S] =
0, central finite differences of the energy and of the gradient (each with a
negative twin that must fail the same check), and the CLI's own numbers.
The statistics, branching, export, render and compare functions against
the CLI: test_cli_parity.py.
"""
import os

import numpy as np
import pytest
import scipy.sparse

import shellspace
from cli_reports import (DOUBLE, DOUBLE_BENT, SQUARE, SQUARE_BENT, cli_json,
                         mesh)


def relative_error(a, b):
    return np.max(np.abs(a - b)) / max(1.0, np.max(np.abs(b)))


# ---- Finite-difference checks (with negative twins) ----------------------

def gradient_error(energy, gradient, x, h=1e-6):
    """max |gradient(x) - central FD of energy| relative to max(1, |FD|)."""
    fd = np.zeros_like(x)
    for i in np.ndindex(x.shape):
        e = np.zeros_like(x)
        e[i] = h
        fd[i] = (energy(x + e) - energy(x - e)) / (2 * h)
    return relative_error(gradient(x), fd)


def hessian_error(gradient, hessian, x, h=1e-6):
    """max |H(x) - central FD of the gradient|, column by column."""
    n = x.size
    fd = np.zeros((gradient(x).size, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        fd[:, j] = (gradient((x.ravel() + e).reshape(x.shape)).ravel() -
                    gradient((x.ravel() - e).reshape(x.shape)).ravel()) / (2 * h)
    return relative_error(hessian(x), fd)


def hessian_matrix(triplets, n):
    rows, cols, vals = triplets
    return scipy.sparse.coo_matrix((vals, (rows, cols)),
                                   shape=(3 * n, 3 * n)).toarray()


@pytest.fixture(scope="module")
def double_square():
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    return V, W, F


def test_read_mesh_shapes_and_types(double_square):
    V, W, F = double_square
    assert V.dtype == np.float64 and V.shape[1] == 3
    assert np.issubdtype(F.dtype, np.integer) and F.shape[1] == 3
    assert W.shape == V.shape


def test_write_read_round_trip(tmp_path, double_square):
    V, W, F = double_square
    path = str(tmp_path / "w.ply")
    shellspace.write_mesh(path, W, F)
    W2, F2 = shellspace.read_mesh(path)
    assert np.array_equal(F2, F)
    assert np.max(np.abs(W2 - W)) == 0.0  # 17 digits written


def test_energy_of_a_mesh_against_itself_is_zero(double_square):
    V, _, F = double_square
    e = shellspace.energy(V, V, F)
    assert abs(e["membrane"]) < 1e-14
    assert abs(e["bending"]) < 1e-14
    assert abs(e["total"]) < 1e-14
    # The default bending weight is relative: eta = 1e-4 x the reference's
    # area (here 1.98, from the triangles directly).
    a, b, c = (V[F[:, i]] for i in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    assert (e["mu"], e["lambda"]) == (1, 1)
    assert shellspace.DEFAULT_RELATIVE_ETA == 1e-4
    assert e["eta"] == pytest.approx(1e-4 * area, rel=1e-14)
    assert shellspace.energy(V, V, F, relative_eta=0.5)["eta"] == \
        pytest.approx(0.5 * area, rel=1e-14)


def test_energy_matches_cli(double_square):
    V, W, F = double_square
    e = shellspace.energy(V, W, F, eta=0.1)
    cli = cli_json(["energy", "--reference", DOUBLE, "--deformed",
                    DOUBLE_BENT, "--eta", "0.1"], quiet=False)
    material = cli.pop("material")  # the CLI's resolved material record
    assert (material["eta"], material["eta_from"]) == (0.1, "absolute")
    assert e == cli
    assert abs(e["total"] - (e["membrane"] + 0.1 * e["bending"])) < 1e-14


def test_bending_model_matches_cli(double_square):
    V, W, F = double_square
    for model in ("discrete-shells", "shape-operator"):
        e = shellspace.energy(V, W, F, bending=model)
        cli = cli_json(["energy", "--reference", DOUBLE, "--deformed",
                        DOUBLE_BENT, "--bending", model], quiet=False)
        material = cli.pop("material")
        assert material["bending_model"] == model
        assert e == cli
    # The two models give different W_bend (the parameter reaches the
    # library), and an unknown model is a Python exception with the message.
    assert shellspace.energy(V, W, F, bending="shape-operator")["bending"] != \
        shellspace.energy(V, W, F)["bending"]
    with pytest.raises(shellspace.InputError, match="unknown bending model"):
        shellspace.energy(V, W, F, bending="plates")


def test_membrane_law_matches_cli(double_square):
    V, W, F = double_square
    for law in ("neo-hookean", "st-venant-kirchhoff"):
        e = shellspace.energy(V, W, F, membrane=law)
        cli = cli_json(["energy", "--reference", DOUBLE, "--deformed",
                        DOUBLE_BENT, "--membrane", law], quiet=False)
        material = cli.pop("material")
        assert material["membrane_law"] == law
        assert e == cli
    # The laws give different W_mem and the same W_bend; an unknown law is a
    # Python exception naming the laws.
    neo = shellspace.energy(V, W, F)
    svk = shellspace.energy(V, W, F, membrane="st-venant-kirchhoff")
    assert svk["membrane"] != neo["membrane"]
    assert svk["bending"] == neo["bending"]
    with pytest.raises(shellspace.InputError,
                       match="unknown membrane law .*st-venant-kirchhoff"):
        shellspace.energy(V, W, F, membrane="hooke")


@pytest.mark.parametrize("side", ["deformed", "reference"])
def test_gradient_against_finite_differences(double_square, side):
    # Derivatives are at a fixed eta: with the default relative eta, moving
    # the reference would also change eta (its area), so eta is given.
    V, W, F = double_square
    if side == "deformed":
        energy = lambda x: shellspace.energy(V, x, F, eta=0.01)["total"]
        gradient = lambda x: shellspace.energy_gradient(V, x, F, side=side,
                                                        eta=0.01)
        x = W
    else:
        energy = lambda x: shellspace.energy(x, W, F, eta=0.01)["total"]
        gradient = lambda x: shellspace.energy_gradient(x, W, F, side=side,
                                                        eta=0.01)
        x = V
    assert np.max(np.abs(gradient(x))) > 1e-2  # a non-trivial point
    assert gradient_error(energy, gradient, x) < 1e-6
    # Negative twin: one wrong entry (1 % off) fails the same check.
    def wrong(y):
        g = gradient(y).copy()
        g[1, 2] *= 1.01
        return g
    assert gradient_error(energy, wrong, x) > 1e-4


@pytest.mark.parametrize("rows,cols", [("deformed", "deformed"),
                                       ("reference", "reference"),
                                       ("reference", "deformed")])
def test_hessian_triplets_against_finite_differences(double_square, rows,
                                                     cols):
    V, W, F = double_square
    n = V.shape[0]

    def args(x):  # (reference, deformed) with the `cols` side at x
        return (x, W) if cols == "reference" else (V, x)

    # At a fixed eta (see test_gradient_against_finite_differences).
    gradient = lambda x: shellspace.energy_gradient(*args(x), F, side=rows,
                                                    eta=0.01)
    hessian = lambda x: hessian_matrix(
        shellspace.energy_hessian(*args(x), F, rows=rows, cols=cols,
                                  eta=0.01), n)
    x = V if cols == "reference" else W
    H = hessian(x)
    if rows == cols:
        assert np.max(np.abs(H - H.T)) < 1e-12 * max(1, np.max(np.abs(H)))
    assert hessian_error(gradient, hessian, x) < 1e-6
    # Negative twin: a symmetric perturbation of one entry pair (0.1 % of
    # the largest entry) fails the same check.
    def wrong(y):
        M = hessian(y).copy()
        M[0, 4] += 1e-3 * np.max(np.abs(M))
        M[4, 0] += 1e-3 * np.max(np.abs(M))
        return M
    assert hessian_error(gradient, wrong, x) > 1e-4


def test_mixed_hessian_is_the_transpose_of_its_twin(double_square):
    V, W, F = double_square
    n = V.shape[0]
    A = hessian_matrix(shellspace.energy_hessian(
        V, W, F, rows="reference", cols="deformed"), n)
    B = hessian_matrix(shellspace.energy_hessian(
        V, W, F, rows="deformed", cols="reference"), n)
    assert np.max(np.abs(A - B.T)) < 1e-12


# ---- Paths --------------------------------------------------------------

def test_geodesic_lm_choice():
    # lm= as the CLI's --lm: the engine's LM stages and Ceres' reach the
    # same geodesic; the stages name who ran; a bad value is an InputError.
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    _, engine = shellspace.geodesic(V, W, F, steps=4, quiet=True, lm="engine")
    _, ceres = shellspace.geodesic(V, W, F, steps=4, quiet=True, lm="ceres")
    assert engine["converged"] and ceres["converged"]
    assert engine["path_energy"] == pytest.approx(ceres["path_energy"],
                                                  rel=1e-8)
    assert engine["stages"][0]["solver"] in ("direct", "block-jacobi")
    assert ceres["stages"][0]["solver"] == "ceres"
    with pytest.raises(shellspace.InputError):
        shellspace.geodesic(V, W, F, steps=4, quiet=True, lm="newton")


def test_geodesic_round_trip_against_cli(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    path, summary = shellspace.geodesic(V, W, F, steps=4, quiet=True,
                                        output=str(tmp_path / "py"))
    cli = cli_json(["geodesic", "--start", DOUBLE, "--end", DOUBLE_BENT,
                    "--steps", "4", "--output", str(tmp_path / "cli")],
                   stop_state=True)
    assert summary["converged"] and cli["converged"]
    assert summary["partial"] is cli["partial"] is False
    assert summary["stop_reason"] == cli["stop_reason"] == ""
    assert abs(summary["path_energy"] - cli["path_energy"]) <= \
        1e-10 * abs(cli["path_energy"])
    assert summary["iterations"] == cli["iterations"]
    drop = {"seconds", "newton_seconds", "output", "multires_levels"}
    assert {k for k in summary} == {k for k in cli}
    for key in set(summary) - drop - {"stages", "step_energies", "init",
                                      "prolongation"}:
        assert summary[key] == pytest.approx(cli[key], rel=1e-10), key
    # The initial path: the same choice and reason (its seconds are wall
    # clock).
    for key in ("requested", "used", "reason", "rigid_motion_removed",
                "linear_turned_faces", "ltheta_iterations"):
        assert summary["init"][key] == cli["init"][key], key
    assert summary["prolongation"] == cli["prolongation"]
    assert path.shape == (5,) + V.shape
    assert np.array_equal(path[0], V) and np.array_equal(path[4], W)
    for k in range(5):
        frame, _ = mesh(str(tmp_path / "cli" / ("shape_%03d.ply" % k)))
        assert np.max(np.abs(frame - path[k])) < 1e-10
        mine, _ = mesh(str(tmp_path / "py" / ("shape_%03d.ply" % k)))
        assert np.max(np.abs(mine - path[k])) == 0.0
    # E_K = K sum_k W[s_{k-1}, s_k], from the energy function itself, with
    # the path's one material (eta resolved on s_0: 1e-4 x its area).
    eta = summary["material"]["eta"]
    assert summary["material"]["eta_from"] == "relative"
    assert eta == pytest.approx(1e-4 * summary["material"]["reference_area"],
                                rel=1e-14)
    parts = [shellspace.energy(path[k - 1], path[k], F, eta=eta)
             for k in range(1, 5)]
    e = sum(p["total"] for p in parts)
    assert abs(4 * e - summary["path_energy"]) < 1e-10 * summary["path_energy"]
    # The membrane / bending split of the report is the same sum by parts.
    split = summary["energy_split"]
    assert split["membrane"] == pytest.approx(
        4 * sum(p["membrane"] for p in parts), rel=1e-12)
    assert split["bending"] == pytest.approx(
        4 * eta * sum(p["bending"] for p in parts), rel=1e-12)
    assert split["membrane"] + split["bending"] == pytest.approx(
        summary["path_energy"], rel=1e-10)


def test_log_then_shoot_returns_to_the_end(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    K = 4
    log, summary = shellspace.log(V, W, F, steps=K, quiet=True)
    geodesic, _ = shellspace.geodesic(V, W, F, steps=K, quiet=True)
    # LOG_K = K (s_1 - s_0) of the geodesic.
    assert np.max(np.abs(log - K * (geodesic[1] - geodesic[0]))) < 1e-12
    assert summary["log_max_norm"] == pytest.approx(np.max(np.abs(log)),
                                                    rel=1e-15)
    # EXP_K of LOG_K: shooting from (s_0, s_0 + LOG_K / K) retraces the
    # geodesic. Inner shapes are defined up to a rigid motion (W is
    # invariant under rigid motions of either argument), so the shapes are
    # compared by W[geodesic_k, shot_k], which is 0 exactly for the same
    # shape up to a rigid motion.
    shot, shoot_summary = shellspace.shoot(V, V + log / K, F, steps=K,
                                           quiet=True)
    assert shoot_summary["converged"]
    assert shot.shape == geodesic.shape
    assert np.max(np.abs(shot[1] - geodesic[1])) < 1e-12
    for k in range(2, K + 1):
        w = shellspace.energy(geodesic[k], shot[k], F)["total"]
        assert w < 1e-12, (k, w)
    assert shoot_summary["path_energy"] == pytest.approx(
        summary["path_energy"], rel=1e-6)
    # The CLI writes start + LOG_K and reports the same E_K.
    out = str(tmp_path / "log.ply")
    cli = cli_json(["log", "--start", DOUBLE, "--end", DOUBLE_BENT, "--steps",
                    str(K), "--output", out])
    assert summary["path_energy"] == pytest.approx(cli["path_energy"],
                                                   rel=1e-10)
    written, _ = mesh(out)
    assert np.max(np.abs(written - (V + log))) < 1e-12


def test_shoot_matches_cli(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    S1 = V + 0.25 * (W - V)
    s1_path = str(tmp_path / "s1.ply")
    shellspace.write_mesh(s1_path, S1, F)
    # allow_unconverged / --allow_unsolved: the numbers are compared
    # whether or not every EXP step met its acceptance (the CLI would exit
    # 4, Python raise NotConvergedError otherwise).
    path, summary = shellspace.shoot(V, S1, F, steps=3, quiet=True,
                                     allow_unconverged=True)
    cli = cli_json(["shoot", "--first", DOUBLE, "--second", s1_path,
                    "--steps", "3", "--output", str(tmp_path / "cli"),
                    "--allow_unsolved"])
    assert summary["path_energy"] == pytest.approx(cli["path_energy"],
                                                   rel=1e-10)
    assert summary["stages"] == cli["stages"]


def test_transport_matches_cli(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    geodesic, _ = shellspace.geodesic(V, W, F, steps=3, quiet=True,
                                      output=str(tmp_path / "path"))
    # The variation: a shear of the first frame.
    varied = V.copy()
    varied[:, 0] += 0.05 * V[:, 1]
    shellspace.write_mesh(str(tmp_path / "varied.ply"), varied, F)
    shapes, summary = shellspace.transport(geodesic, varied, F, quiet=True)
    cli = cli_json(["transport", "--path", str(tmp_path / "path"),
                    "--variation", str(tmp_path / "varied.ply"), "--output",
                    str(tmp_path / "out")])
    assert summary["frames"] == cli["frames"] == 4
    assert shapes.shape == (4,) + V.shape
    assert np.array_equal(shapes[0], varied)
    assert summary["variation_max_norms"] == pytest.approx(
        cli["variation_max_norms"], rel=1e-10)
    assert max(summary["exp_residuals"]) < 1e-8
    for k in range(4):
        frame, _ = mesh(str(tmp_path / "out" / ("shape_%03d.ply" % k)))
        assert np.max(np.abs(frame - shapes[k])) < 1e-10
    # A zero variation is transported as zero (to the EXP steps' solver
    # tolerance): the shapes are the path.
    same, zero = shellspace.transport(geodesic, V, F, quiet=True)
    assert zero["variation_max_norms"][0] == 0.0
    assert max(zero["variation_max_norms"]) < 1e-6
    assert np.max(np.abs(same - geodesic)) < 1e-6


def test_mean_of_two_copies_is_that_shape():
    V, F = mesh(DOUBLE_BENT)
    mean, summary = shellspace.mean([V, V], F, quiet=True)
    assert summary["inputs"] == 2 and summary["converged"]
    assert summary["energy"] < 1e-20
    assert np.max(np.abs(mean - V)) < 1e-8


def test_spline_and_regression_hit_their_data():
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    M = 0.5 * (V + W)
    path, summary = shellspace.spline([V, M, W], [0, 2, 4], F, steps=4,
                                      quiet=True)
    assert path.shape == (5,) + V.shape
    for k, S in ((0, V), (2, M), (4, W)):
        assert np.array_equal(path[k], S)
    assert summary["method"] == "nonlinear" and summary["frames"] == 5
    assert summary["init"] == "ltheta" and "ltheta" in summary
    # From the piecewise geodesic: the keyframes exact, its two segments
    # reported, no LΘA reconstruction.
    geo_path, geo = shellspace.spline([V, M, W], [0, 2, 4], F, steps=4,
                                      init="geodesic", quiet=True)
    for k, S in ((0, V), (2, M), (4, W)):
        assert np.array_equal(geo_path[k], S)
    assert geo["init"] == "geodesic" and "ltheta" not in geo
    assert [(s["from"], s["to"]) for s in geo["init_segments"]] == [(0, 2),
                                                                    (2, 4)]
    with pytest.raises(ValueError, match="needs method nonlinear"):
        shellspace.spline([V, M, W], [0, 2, 4], F, steps=4, method="ltheta",
                          init="geodesic", quiet=True)
    # (Not converged in 200 L-BFGS iterations at this sigma: allowed, the
    # ends are what is checked.)
    path, summary = shellspace.regress([V, W], [0, 4], F, steps=4,
                                       sigma=1e-6, quiet=True,
                                       allow_unconverged=True)
    assert summary["sigma"] == 1e-6
    # A tiny spline weight: the data term wins, the ends stay at the data.
    assert relative_error(path[0], V) < 1e-3
    assert relative_error(path[4], W) < 1e-3


# ---- Errors -------------------------------------------------------------

def test_errors_raise_with_the_library_message(tmp_path):
    V, F = mesh(SQUARE)
    W, _ = mesh(SQUARE_BENT)
    with pytest.raises(ValueError, match="deformed has 3 vertices"):
        shellspace.energy(V, W[:3], F)
    with pytest.raises(shellspace.InputError, match="multires must be auto"):
        shellspace.geodesic(V, W, F, multires="two", quiet=True)
    with pytest.raises(ValueError, match="steps must be >= 1"):
        shellspace.geodesic(V, W, F, steps=0, quiet=True)
    with pytest.raises(ValueError, match="mu"):
        shellspace.energy(V, W, F, mu=-1)
    with pytest.raises(ValueError, match="no_such_file.ply"):
        shellspace.read_mesh(str(tmp_path / "no_such_file.ply"))
    bad = F.copy()
    bad[0, 0] = 99
    with pytest.raises(ValueError, match="face 0"):
        shellspace.energy(V, W, bad)
    with pytest.raises(ValueError, match="mask: vertex index 7"):
        shellspace.shoot(V, W, F, steps=2, mask=[7], quiet=True)
    with pytest.raises(ValueError, match="#V x 3"):
        shellspace.energy(V[:, :2], W, F)
    # The solver keywords have the CLI flags' ranges (UserSolverSettings).
    with pytest.raises(ValueError, match=r"tolerance must be in \(0, 1\)"):
        shellspace.geodesic(V, W, F, tolerance=1.5, quiet=True)
    with pytest.raises(ValueError, match=r"threads must be in \[1, 1024\]"):
        shellspace.geodesic(V, W, F, threads=0, quiet=True)
    # Refused before the simulation runs, as --delta_extrapolation is.
    with pytest.raises(ValueError, match=r"must be 0 or in \[2, 16\], got 17"):
        shellspace.branching_simulate(nx=8, ny=32, delta_extrapolation=17)
    assert not os.listdir(tmp_path)
