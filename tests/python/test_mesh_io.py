import numpy as np
import pytest

import geodual
from conftest import grid_plane


def test_read_mesh_shapes_and_dtypes(data_dir):
    V, F = geodual.read_mesh(data_dir / "bunny.ply")
    assert V.shape == (35947, 3) and V.dtype == np.float64
    assert F.shape == (69451, 3) and F.dtype == np.int32
    assert F.min() >= 0 and F.max() < len(V)
    # The bunny is about 0.25 units across (tests/data/README.md: bbox diagonal 0.2502).
    used = V[np.unique(F)]
    assert np.linalg.norm(used.max(axis=0) - used.min(axis=0)) == pytest.approx(0.2502, abs=5e-4)


def test_read_mesh_takes_str_paths_and_colors_flag(data_dir):
    V, F, C = geodual.read_mesh(str(data_dir / "woody.ply"), colors=True)
    assert V.shape == (694, 3) and F.shape == (1267, 3)
    assert C is None  # woody.ply has no colours


@pytest.mark.parametrize("extension", [".ply", ".obj"])
def test_write_read_round_trip_is_exact(tmp_path, extension):
    V, F = grid_plane(7)
    rng = np.random.default_rng(5)
    V = V + rng.normal(scale=0.01, size=V.shape)  # coordinates with all 17 digits
    path = tmp_path / ("mesh" + extension)
    geodual.write_mesh(path, V, F)
    V2, F2 = geodual.read_mesh(path)
    np.testing.assert_array_equal(V2, V)
    np.testing.assert_array_equal(F2, F)


def test_write_mesh_casts_numeric_dtypes(tmp_path):
    V, F = grid_plane(4)
    path = tmp_path / "cast.ply"
    geodual.write_mesh(path, V.astype(np.float32), F.astype(np.uint64), colors=np.zeros((16, 3), np.uint8))
    V2, F2 = geodual.read_mesh(path)
    np.testing.assert_array_equal(V2, V.astype(np.float32).astype(np.float64))
    np.testing.assert_array_equal(F2, F)


def test_write_mesh_refuses_an_unknown_extension_and_writes_nothing(tmp_path):
    V, F = grid_plane(3)
    with pytest.raises(geodual.Error, match=r"\.xyz"):
        geodual.write_mesh(tmp_path / "mesh.xyz", V, F)
    assert list(tmp_path.iterdir()) == []


def test_missing_file_error_names_the_path(tmp_path):
    missing = tmp_path / "no_such_scan.ply"
    with pytest.raises(geodual.Error) as error:
        geodual.read_mesh(missing)
    assert str(missing) in str(error.value)
    assert isinstance(error.value, RuntimeError)


def test_bad_file_error_names_the_path(tmp_path):
    bad = tmp_path / "broken.ply"
    bad.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n")
    with pytest.raises(geodual.Error, match="broken.ply"):
        geodual.read_mesh(bad)


@pytest.mark.parametrize(
    "V, F, error, message",
    [
        (np.zeros((4, 2)), [[0, 1, 2]], ValueError, r"V must be an n x 3 array, got shape \(4, 2\)"),
        (np.zeros(12), [[0, 1, 2]], ValueError, r"V must be an n x 3 array, got shape \(12,\)"),
        (np.zeros((4, 3)), [[0, 1, 4]], ValueError, r"F\[0\] refers to vertex 4, out of range: V has 4 rows"),
        (np.zeros((4, 3)), [[0, 1, -1]], ValueError, r"out of range"),
        (np.zeros((4, 3)), [[0, 1]], ValueError, r"F must be an n x 3 array"),
        (np.zeros((4, 3)), np.zeros((0, 3), np.int32), ValueError, r"at least one triangle"),
        (np.zeros((4, 3)), [[0, 1, 2.5]], ValueError, r"not an integer"),
        ([[0, 0, 0], [1, 0, np.nan], [0, 1, 0]], [[0, 1, 2]], ValueError, r"V\[1\] is not finite"),
        (np.array([["a", "b", "c"]]), [[0, 0, 0]], TypeError, r"V must have a real or integer dtype"),
    ],
)
def test_bad_arrays_raise_clear_errors(tmp_path, V, F, error, message):
    with pytest.raises(error, match=message):
        geodual.write_mesh(tmp_path / "bad.ply", V, F)
    assert not (tmp_path / "bad.ply").exists()


def test_bad_colors_raise_clear_errors(tmp_path):
    V, F = grid_plane(3)
    with pytest.raises(ValueError, match="colors has 2 rows for 9 vertices"):
        geodual.write_mesh(tmp_path / "c.ply", V, F, colors=np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"colors\[4\] is not in \[0, 1\]"):
        colors = np.zeros((9, 4))
        colors[4, 3] = 1.5
        geodual.write_mesh(tmp_path / "c.ply", V, F, colors=colors)


@pytest.mark.parametrize("extension", [".ply", ".obj", ".glb"])
def test_colors_round_trip_through_every_format(tmp_path, extension):
    V, F = grid_plane(5)
    rng = np.random.default_rng(9)
    C = rng.integers(0, 256, size=(len(V), 3), dtype=np.uint8)
    path = tmp_path / ("coloured" + extension)
    geodual.write_mesh(path, V, F, colors=C)
    V2, F2, C2 = geodual.read_mesh(path, colors=True)
    assert C2 is not None and C2.shape == (len(V), 3) and C2.dtype == np.float32
    # PLY keeps the bytes; OBJ prints k / 255 exactly; glTF's linear COLOR_0 (float32) comes back within rounding.
    tolerance = 1e-6 if extension == ".glb" else 0
    np.testing.assert_allclose(C2 * 255, C.astype(np.float64), atol=255 * tolerance + 1e-4)


@pytest.mark.parametrize("compress,extension", [("meshopt", "EXT_meshopt_compression"),
                                                ("draco", "KHR_draco_mesh_compression")])
def test_write_mesh_compresses_gltf_which_read_mesh_refuses_by_name(tmp_path, compress, extension):
    V, F = grid_plane(20)
    plain, packed = tmp_path / "plain.glb", tmp_path / f"{compress}.glb"
    geodual.write_mesh(plain, V, F)
    geodual.write_mesh(packed, V, F, compress=compress)
    assert packed.stat().st_size < plain.stat().st_size
    assert extension.encode() in packed.read_bytes()
    with pytest.raises(geodual.Error, match=extension) as error:
        geodual.read_mesh(packed)
    assert str(packed) in str(error.value)


def test_write_mesh_refuses_compress_for_other_formats_and_unknown_names(tmp_path):
    V, F = grid_plane(3)
    with pytest.raises(ValueError, match=r"compress='meshopt'.*mesh\.ply"):
        geodual.write_mesh(tmp_path / "mesh.ply", V, F, compress="meshopt")
    with pytest.raises(ValueError, match="'zip'"):
        geodual.write_mesh(tmp_path / "mesh.glb", V, F, compress="zip")
    assert list(tmp_path.iterdir()) == []
