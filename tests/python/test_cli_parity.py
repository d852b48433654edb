"""The module's statistics, branching, export, render and compare functions
against the CLI (python/module_*.cc): the same summaries to 1e-10, the same
mode shapes, the same .glb and PNG bytes, the same comparison numbers; on
the shared double square (cli_reports.py).

Run by CTest (`python_tests`), as test_shellspace.py.
"""
import json
import os
import subprocess

import numpy as np
import pytest

import shellspace
from cli_reports import CLI, DOUBLE, DOUBLE_BENT, cli_json, mesh


# ---- Statistics and branching against the CLI ----------------------------

def without_times(summary):
    """The summary without wall-clock entries and the output path."""
    if isinstance(summary, dict):
        return {k: without_times(v) for k, v in summary.items()
                if "seconds" not in k and k not in ("output", "far_inputs")}
    if isinstance(summary, list):
        return [without_times(v) for v in summary]
    return summary


def assert_same_numbers(a, b, rel=1e-10):
    assert type(a) == type(b) or {type(a), type(b)} <= {int, float}, (a, b)
    if isinstance(a, dict):
        assert set(a) == set(b)
        for k in a:
            assert_same_numbers(a[k], b[k], rel)
    elif isinstance(a, list):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            assert_same_numbers(x, y, rel)
    elif isinstance(a, float) or isinstance(b, float):
        assert a == pytest.approx(b, rel=rel, abs=1e-14)
    else:
        assert a == b


def test_pca_matches_cli(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    frames, _ = shellspace.geodesic(V, W, F, steps=2, quiet=True,
                                    output=str(tmp_path / "in"))
    inputs = [frames[0], frames[1], frames[2]]
    shapes, summary = shellspace.pca(inputs, F, modes=1, baseline="procrustes",
                                     quiet=True, output=str(tmp_path / "py"))
    files = ",".join(str(tmp_path / "in" / ("shape_%03d.ply" % k))
                     for k in range(3))
    cli = cli_json(["pca", "--inputs", files, "--modes", "1", "--baseline",
                    "procrustes", "--output", str(tmp_path / "cli")],
                   stop_state=True)
    cli.pop("converged")  # the verb's verdict, not part of the model
    assert_same_numbers(without_times(summary), without_times(cli))
    assert sorted(shapes) == sorted(
        f[:-4] for f in os.listdir(tmp_path / "cli") if f.endswith(".ply"))
    for name, shape in shapes.items():
        written, _ = mesh(str(tmp_path / "cli" / (name + ".ply")))
        assert np.max(np.abs(written - shape)) < 1e-10, name
    # Both directories hold the run's summary.json, as the CLI writes it.
    assert sorted(os.listdir(tmp_path / "py")) == sorted(
        os.listdir(tmp_path / "cli"))
    with pytest.raises(ValueError, match="modes 3 exceeds 2"):
        shellspace.pca(inputs, F, modes=3, quiet=True)


def test_branching_construct_matches_cli(tmp_path):
    for family in ("km", "lens"):
        summary = shellspace.branching_construct(family=family, epsilon=0.002)
        cli = cli_json(["branching", "construct", "--family", family,
                        "--epsilon", "0.002", "--output",
                        str(tmp_path / family)])
        assert_same_numbers(without_times(summary), without_times(cli))
    km = shellspace.branching_construct()
    assert km["constant"] == pytest.approx(km["km_shifted_constant_closed_form"],
                                           rel=1e-6)
    with pytest.raises(ValueError, match="family must be"):
        shellspace.branching_construct(family="tree")


def test_branching_simulate_matches_cli(tmp_path):
    args = dict(nx=8, ny=32, continuation=1, lm_iterations=30)
    u, summary = shellspace.branching_simulate(**args)
    cli = cli_json(["branching", "simulate", "--nx", "8", "--ny", "32",
                    "--continuation", "1", "--lm_iterations", "30",
                    "--output", str(tmp_path / "sim")], stop_state=True)
    assert_same_numbers(without_times(summary), without_times(cli))
    assert u.shape == (9, 32)
    csv = np.loadtxt(tmp_path / "sim" / "u.csv", delimiter=",", skiprows=1)
    assert np.max(np.abs(csv[:, 4] - u.ravel())) < 1e-10


def test_gltf_of_a_path_is_the_clis_export(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    frames, _ = shellspace.geodesic(V, W, F, steps=3, quiet=True,
                                    output=str(tmp_path / "frames"),
                                    gltf=str(tmp_path / "geodesic.glb"))
    shellspace.write_gltf(str(tmp_path / "py.glb"), frames, F,
                          interpolation="step", fps=2)
    subprocess.run([CLI, "export", "--input", str(tmp_path / "frames"),
                    "--output", str(tmp_path / "cli.glb"), "--interpolation",
                    "step", "--fps", "2", "--quiet"], check=True)
    py = (tmp_path / "py.glb").read_bytes()
    assert py[:4] == b"glTF" and py == (tmp_path / "cli.glb").read_bytes()
    assert (tmp_path / "geodesic.glb").read_bytes()[:4] == b"glTF"
    with pytest.raises(ValueError, match="interpolation must be"):
        shellspace.write_gltf(str(tmp_path / "x.glb"), frames, F,
                              interpolation="cubic")
    with pytest.raises(ValueError, match="missing"):
        shellspace.geodesic(V, W, F, steps=2, quiet=True,
                            output=str(tmp_path / "none"),
                            gltf=str(tmp_path / "missing" / "a.glb"))
    assert not (tmp_path / "none").exists()


def test_film_strip_is_the_clis_render(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    frames, _ = shellspace.geodesic(V, W, F, steps=3, quiet=True,
                                    output=str(tmp_path / "frames"))
    shellspace.write_film_strip(str(tmp_path / "py.png"), frames, F,
                                width=400, up="z", color="displacement")
    subprocess.run([CLI, "render", "--input", str(tmp_path / "frames"),
                    "--output", str(tmp_path / "cli.png"), "--width", "400",
                    "--up", "z", "--color", "displacement", "--quiet"],
                   check=True)
    py = (tmp_path / "py.png").read_bytes()
    assert py[1:4] == b"PNG" and py == (tmp_path / "cli.png").read_bytes()
    # IHDR: the whole image is 400 pixels wide.
    assert int.from_bytes(py[16:20], "big") == 400
    with pytest.raises(ValueError, match="bad up axis"):
        shellspace.write_film_strip(str(tmp_path / "x.png"), frames, F,
                                    up="sideways")
    assert not (tmp_path / "x.png").exists()


def test_compare_matches_cli_for_meshes_and_paths(tmp_path):
    V, F = mesh(DOUBLE)
    W, _ = mesh(DOUBLE_BENT)
    # Two meshes: the CLI's numbers (its exit 1 says they differ).
    mine = shellspace.compare(V, W, F)
    out = subprocess.run([CLI, "compare", "--json", "--a", DOUBLE, "--b",
                          DOUBLE_BENT], capture_output=True, text=True)
    assert out.returncode == 1
    cli = json.loads(out.stdout)
    assert not mine["equal"] and not cli["equal"]
    for key in ("max_distance", "mean_distance", "energy_a_to_b"):
        assert mine[key] == pytest.approx(cli[key], rel=1e-12), key
    assert mine["energy_a_to_b"] == pytest.approx(
        shellspace.energy(V, W, F)["total"], rel=1e-12)
    # A path against itself rigidly moved (a rotation about z by 90
    # degrees): equal, with the same E_K.
    path, _ = shellspace.geodesic(V, W, F, steps=3, quiet=True,
                                  output=str(tmp_path / "path"))
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    moved = [frame @ turn.T + 1.0 for frame in path]
    same = shellspace.compare(list(path), moved, F)
    assert same["equal"] and same["frames"] == 4
    assert same["max_distance"] < 1e-12
    assert same["relative_energy_difference"] < 1e-12
    cli = cli_json(["compare", "--a", str(tmp_path / "path"), "--b",
                    str(tmp_path / "path")])
    assert cli["path_energy_a"] == pytest.approx(same["path_energy_a"],
                                                 rel=1e-10)
    with pytest.raises(Exception, match="frames"):
        shellspace.compare(list(path), list(path)[:2], F)
