"""Procedural meshes of the Python tests (no data folder needed)."""
import numpy as np


def plate(n=5):
    """An n x n grid on the unit square, two triangles per cell: (V, F)."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    V = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1)
    F = []
    for r in range(n - 1):
        for c in range(n - 1):
            a = r * n + c
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return V, np.array(F, dtype=np.int64)


def bent_plates(count=5, n=6):
    """count x (n x n) plates: the plate bent about y by a different amount and twisted a little."""
    V, F = plate(n)
    shapes = []
    for k in range(count):
        S = V.copy()
        S[:, 2] = 0.12 * k * (S[:, 0] - 0.5) ** 2 + 0.03 * k * (
            S[:, 0] - 0.5) * (S[:, 1] - 0.5)
        shapes.append(S)
    return np.stack(shapes), F
