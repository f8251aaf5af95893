import numpy as np
import pytest

import geodual
from conftest import grid_plane


def euclidean_nearest(V, site_positions):
    d = np.linalg.norm(V[:, None, :] - site_positions[None, :, :], axis=2)
    order = np.sort(d, axis=1)
    return d.min(axis=1), d.argmin(axis=1), order[:, 1] - order[:, 0]


def face_point(V, F, face, u, v, w):
    return u * V[F[face, 0]] + v * V[F[face, 1]] + w * V[F[face, 2]]


def test_geodesic_on_a_plane_is_the_euclidean_distance(plane):
    V, F = plane
    sites = [0, 227, (301, 0.2, 0.3, 0.5), (640, 0.6, 0.1, 0.3)]
    positions = np.array([V[0], V[227], face_point(V, F, 301, 0.2, 0.3, 0.5), face_point(V, F, 640, 0.6, 0.1, 0.3)])
    distance, nearest = geodual.geodesic(V, F, sites)
    assert distance.dtype == np.float64 and distance.shape == (len(V),)
    assert nearest.dtype == np.int32 and nearest.shape == (len(V),)
    expected, expected_site, gap = euclidean_nearest(V, positions)
    np.testing.assert_allclose(distance, expected, rtol=1e-9, atol=1e-12)
    assert distance[0] == 0 and distance[227] == 0
    assert nearest[0] == 0 and nearest[227] == 1
    clear = gap > 1e-9  # vertices not (numerically) on a bisector
    assert clear.sum() > 0.9 * len(V)
    np.testing.assert_array_equal(nearest[clear], expected_site[clear])


def test_geodesic_takes_a_k_x_4_array_of_face_points(plane):
    V, F = plane
    sites = np.array([[10, 1 / 3, 1 / 3, 1 / 3], [700, 0.5, 0.25, 0.25]])
    distance, nearest = geodual.geodesic(V, F, sites)
    positions = np.array([face_point(V, F, int(f), u, v, w) for f, u, v, w in sites])
    expected, _, _ = euclidean_nearest(V, positions)
    np.testing.assert_allclose(distance, expected, rtol=1e-9, atol=1e-12)


def test_geodesic_is_unreachable_on_another_component():
    V, F = grid_plane(3)
    V2 = np.vstack([V, V + [5, 0, 0]])
    F2 = np.vstack([F, F + len(V)])
    distance, nearest = geodual.geodesic(V2, F2, np.array([0], dtype=np.int64))
    assert np.all(np.isfinite(distance[: len(V)])) and np.all(nearest[: len(V)] == 0)
    assert np.all(np.isinf(distance[len(V) :])) and np.all(nearest[len(V) :] == -1)


def test_geodesic_site_errors(plane):
    V, F = plane
    with pytest.raises(ValueError, match="vertex index 441 out of range: the mesh has 441 vertices"):
        geodual.geodesic(V, F, [441])
    with pytest.raises(ValueError, match="face index 800 out of range"):
        geodual.geodesic(V, F, [(800, 1, 0, 0)])
    with pytest.raises(TypeError, match=r"\(face, u, v, w\)"):
        geodual.geodesic(V, F, [(1, 0.5, 0.5)])
    with pytest.raises(ValueError, match="sites is empty"):
        geodual.geodesic(V, F, [])
    with pytest.raises(geodual.Error):  # the engine's own check: two sites at one point
        geodual.geodesic(V, F, [3, 3])


def test_voronoi_boundaries_lie_on_the_perpendicular_bisectors(plane):
    V, F = plane
    # (0.2, 0.2), (0.8, 0.3) and a point near (0.42, 0.82): their circumcentre is inside the square.
    sites = [88, 142, (656, 0.2, 0.5, 0.3)]
    positions = np.array([V[88], V[142], face_point(V, F, 656, 0.2, 0.5, 0.3)])
    diagram = geodual.voronoi(V, F, sites)
    np.testing.assert_allclose(diagram["sites"], positions)
    polylines, separated = diagram["polylines"], diagram["polyline_sites"]
    assert len(polylines) == 3 and separated.shape == (3, 2)
    assert {tuple(sorted(pair)) for pair in separated.tolist()} == {(0, 1), (0, 2), (1, 2)}
    for points, (left, right) in zip(polylines, separated):
        assert points.ndim == 2 and points.shape[1] == 3 and len(points) >= 2
        to_left = np.linalg.norm(points - positions[left], axis=1)
        to_right = np.linalg.norm(points - positions[right], axis=1)
        np.testing.assert_allclose(to_left, to_right, rtol=0, atol=1e-9)
        np.testing.assert_allclose(points[:, 2], 0, atol=1e-15)
    # One Voronoi vertex: the circumcentre of the three sites, inside the square.
    assert diagram["vertices"].shape == (1, 3)
    centre = diagram["vertices"][0]
    radii = np.linalg.norm(positions - centre, axis=1)
    np.testing.assert_allclose(radii, radii[0], rtol=1e-9)
    assert diagram["vertex_distance"][0] == pytest.approx(radii[0], rel=1e-9)
    assert sorted(diagram["vertex_sites"][0].tolist()) == [0, 1, 2]
    # The cells tile the square.
    assert diagram["cell_area"].sum() == pytest.approx(1.0, rel=1e-9)
    np.testing.assert_array_equal(diagram["nearest_site"], geodual.geodesic(V, F, sites)[1])
