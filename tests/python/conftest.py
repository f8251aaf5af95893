# Shared inputs of the Python module's tests: the repository's test meshes and
# flat grids built here. ctest runs these with PYTHONPATH=<build>/python.
import pathlib

import numpy as np
import pytest

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"


def grid_plane(n, size=1.0):
    """An n x n vertex grid on [0, size]^2 in the plane z = 0, two triangles per
    square, counter-clockwise seen from +z."""
    xs = np.linspace(0.0, size, n)
    x, y = np.meshgrid(xs, xs, indexing="xy")
    V = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i, (j + 1) * n + i + 1
            faces += [(a, b, d), (a, d, c)]
    return V, np.array(faces, dtype=np.int32)


@pytest.fixture
def plane():
    return grid_plane(21)


@pytest.fixture
def data_dir():
    return DATA
