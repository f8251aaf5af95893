import os
import signal
import threading

import numpy as np
import pytest

import geodual
from conftest import grid_plane

# The keys `geodual stats --json` prints, less its paths and times
# (tests/cli/stats_command_test.cpp checks the CLI's).
STATS_KEYS = [
    "vertices", "faces", "degenerate_faces", "q_min", "q_avg", "theta_min_deg", "theta_min_avg_deg",
    "pct_angles_lt30", "p30", "valence_histogram", "interior_vertices", "pct_valence6",
    "euler_characteristic", "genus", "components", "boundary_loops", "nonmanifold_edges", "bbox_diagonal",
    "area", "volume", "hausdorff", "rms", "hausdorff_pct", "rms_pct", "hausdorff_reference_to_candidate_pct",
    "hausdorff_candidate_to_reference_pct", "hausdorff_at", "area_change_pct", "volume_change_pct", "sharp_angle_deg",
    "feature_tolerance_pct", "feature_recall_edges", "feature_recall_length", "feature_recall_pct",
    "feature_max_gap_pct", "samples_per_side", "seed", "reference_samples", "candidate_samples",
    "reference_quality",
]


@pytest.fixture(scope="module")
def fertility():
    return geodual.read_mesh(os.path.join(os.path.dirname(__file__), "..", "data", "fertility.ply"))


@pytest.fixture(scope="module")
def woody():
    return geodual.read_mesh(os.path.join(os.path.dirname(__file__), "..", "data", "woody.ply"))


def test_remesh_2000_sites_gives_2000_vertices_and_the_stats(fertility):
    V, F = fertility
    result = geodual.remesh(V, F, sites=2000)
    # Fertility is one closed piece: no sites are needed for boundary loops,
    # and on this mesh the repair adds none, so the count is exact.
    assert result.sites == 2000
    assert result.sites_added == 0 and result.sites_left_out == 0 and result.sites_added_for_topology == 0
    assert result.sites_added_near_features == 0
    assert result.vertices.shape == (2000, 3) and result.vertices.dtype == np.float64
    assert result.faces.dtype == np.int32 and result.faces.shape[1] == 3
    assert result.faces.min() >= 0 and result.faces.max() < 2000
    assert result.colors is None
    stats = result.stats
    assert list(stats) == STATS_KEYS
    assert stats["vertices"] == 2000 and stats["faces"] == len(result.faces)
    # Genus 4, closed: chi = 2 - 2g = -6, kept by the remesh; F = 2(V - chi).
    assert stats["genus"] == 4 and stats["euler_characteristic"] == -6 and stats["boundary_loops"] == 0
    assert len(result.faces) == 2 * (2000 + 6)
    assert 0.5 < stats["q_avg"] < 1 and 0 < stats["q_min"] <= stats["q_avg"]
    assert 0 < stats["hausdorff_pct"] < 2 and 0 < stats["rms_pct"] < stats["hausdorff_pct"]
    assert abs(stats["area_change_pct"]) < 2
    assert stats["reference_quality"]["vertices"] == len(V)
    assert stats["reference_quality"]["faces"] == len(F)
    assert set(result.timings) == {"sample", "relax", "dual", "statistics"}
    # Remesh vertices lie on the input: within the Hausdorff distance of it.
    assert np.all(result.vertices.min(axis=0) >= V.min(axis=0) - 1e-9)
    assert np.all(result.vertices.max(axis=0) <= V.max(axis=0) + 1e-9)


def test_remesh_report_is_the_cli_json_less_paths_and_times(woody, tmp_path):
    # One report (pipeline::remesh_report_json) for Python and the CLI: the
    # same figures for the same mesh, options and seed.
    import json
    import subprocess
    V, F = woody
    result = geodual.remesh(V, F, sites=300, statistics=False)
    report = result.report
    assert report["vertices"] == len(result.vertices) and report["faces"] == len(result.faces)
    assert report["sites"] == result.sites and report["sites_added"] == result.sites_added
    assert report["sampling"] == "poisson" and report["seed"] == 1
    assert report["q_min"] == result.stats["q_min"]
    cli = os.environ["GEODUAL_CLI"]  # set by ctest
    mesh = os.path.join(os.path.dirname(__file__), "..", "data", "woody.ply")
    run = subprocess.run([cli, "remesh", mesh, "--sites", "300", "--samples", "-1", "--json", "--quiet",
                          "-o", str(tmp_path / "woody.ply")], capture_output=True, text=True, check=True)
    figures = json.loads(run.stdout)
    for key in ("mesh", "output", "compress", "attributes", "time_s", "peak_memory_bytes"):
        figures.pop(key)
    figures = {k: v for k, v in figures.items() if not k.endswith("_s")}
    assert list(figures) == list(report)
    assert figures == report


def test_remesh_is_deterministic_and_seeded(woody):
    V, F = woody
    a = geodual.remesh(V, F, sites=200, lloyd=3, statistics=False)
    b = geodual.remesh(V, F, sites=200, lloyd=3, statistics=False)
    c = geodual.remesh(V, F, sites=200, lloyd=3, statistics=False, seed=2)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_array_equal(a.faces, b.faces)
    assert not np.array_equal(a.vertices, c.vertices)
    # Without statistics, the remesh's own quality figures only.
    assert a.stats["vertices"] == len(a.vertices) and "hausdorff" not in a.stats
    assert "statistics" not in a.timings


def test_keeping_freed_memory_in_the_heap_changes_no_result(woody):
    V, F = woody
    before = geodual.remesh(V, F, sites=200, lloyd=3, statistics=False)
    assert geodual.keep_freed_memory_in_heap() is None
    after = geodual.remesh(V, F, sites=200, lloyd=3, statistics=False)
    np.testing.assert_array_equal(before.vertices, after.vertices)
    np.testing.assert_array_equal(before.faces, after.faces)


def test_remesh_sizing_by_edge_length_and_faces(woody):
    V, F = woody
    by_faces = geodual.remesh(V, F, faces=400, lloyd=2, statistics=False)
    assert 300 < len(by_faces.faces) < 500
    edges = np.concatenate([by_faces.faces[:, [0, 1]], by_faces.faces[:, [1, 2]], by_faces.faces[:, [2, 0]]])
    mean_edge = np.linalg.norm(by_faces.vertices[edges[:, 0]] - by_faces.vertices[edges[:, 1]], axis=1).mean()
    by_length = geodual.remesh(V, F, edge_length=mean_edge, lloyd=2, statistics=False)
    assert 0.7 * len(by_faces.faces) < len(by_length.faces) < 1.3 * len(by_faces.faces)


def test_remesh_with_given_sites_keeps_them(woody):
    V, F = woody
    sites = list(range(0, 694, 7))
    result = geodual.remesh(V, F, sites=sites, lloyd=0, statistics=False)
    assert result.sites == len(sites)
    n = len(sites) + result.sites_added - result.sites_left_out
    assert len(result.vertices) == n
    if result.sites_left_out == 0:
        np.testing.assert_array_equal(result.vertices[: len(sites)], V[sites])


def test_colors_of_a_linear_field_come_back_linear():
    V, F = grid_plane(31)
    V[:, 2] = 0.3 * V[:, 0] - 0.2 * V[:, 1]  # a tilted plane, still flat
    colors = np.column_stack([V[:, 0], 1 - V[:, 1], 0.5 * V[:, 0] + 0.25 * V[:, 1] + 0.1])
    result = geodual.remesh(V, F, sites=150, lloyd=2, colors=colors, statistics=False)
    assert result.colors.dtype == np.float32 and result.colors.shape == (len(result.vertices), 3)
    x, y = result.vertices[:, 0], result.vertices[:, 1]
    expected = np.column_stack([x, 1 - y, 0.5 * x + 0.25 * y + 0.1])
    np.testing.assert_allclose(result.colors, expected, rtol=0, atol=1e-4)
    # RGBA stays RGBA.
    rgba = np.column_stack([colors, np.full(len(V), 0.5)])
    result = geodual.remesh(V, F, sites=150, lloyd=0, colors=rgba, statistics=False)
    assert result.colors.shape == (len(result.vertices), 4)
    np.testing.assert_allclose(result.colors[:, 3], 0.5, atol=1e-6)


def test_feature_edges_are_kept_as_edges_of_the_remesh():
    # A flat grid with its middle row given as a feature: no angle, still kept.
    n = 21
    V, F = grid_plane(n)
    row = np.arange(n) + (n // 2) * n  # y = 0.5, from x = 0 to 1
    edges = np.column_stack([row[:-1], row[1:]])
    result = geodual.remesh(V, F, sites=120, lloyd=2, feature_edges=edges, statistics=False)
    a = result.vertices[result.faces[:, [0, 1, 2]].ravel()]
    b = result.vertices[result.faces[:, [1, 2, 0]].ravel()]
    for x in np.linspace(0.0, 1.0, 41):
        p = np.array([x, 0.5, 0.0])
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
        gap = np.min(np.linalg.norm(a + t[:, None] * d - p, axis=1))
        assert gap < 1e-9, (x, gap)
    with pytest.raises(geodual.UsageError, match="feature edge 0 2: not an edge"):
        geodual.remesh(V, F, sites=120, feature_edges=[[0, 2]])
    with pytest.raises(TypeError, match="feature_edges must be a k x 2 array"):
        geodual.remesh(V, F, sites=120, feature_edges=[[0.0, 1.0]])
    with pytest.raises(TypeError, match="feature_edges must be a k x 2 array"):
        geodual.remesh(V, F, sites=120, feature_edges=[0, 1, 2])


def test_narrowest_corner_between_the_kept_creases(data_dir):
    # fandisk's creases meet at 19.4 degrees at their narrowest corner.
    V, F = geodual.read_mesh(data_dir / "fandisk.ply")
    kept = geodual.remesh(V, F, sites=2000, statistics=False)
    assert kept.narrowest_corner == pytest.approx(19.4, abs=0.05)
    assert geodual.remesh(V, F, sites=2000, sharp_angle=0, statistics=False).narrowest_corner is None


def test_says_which_features_were_kept_and_where_creases_were_left_out(data_dir):
    V, F = geodual.read_mesh(data_dir / "fandisk.ply")
    kept = geodual.remesh(V, F, sites=2000, statistics=False)
    assert kept.feature_chains >= 30
    assert kept.features_dropped_reason is None
    assert kept.features_dropped_near.shape == (0, 3)
    # OpenSCAD's surface_image at 500 sites: the remesh that keeps its creases
    # fails at one place; those near it are left out, the others kept.
    V, F = geodual.read_mesh(data_dir / "cad" / "surface_image.stl")
    partly = geodual.remesh(V, F, sites=500, statistics=False)
    assert partly.feature_chains > 0
    assert partly.features_dropped_reason is None
    assert partly.features_dropped_near.shape == (1, 3)
    lo, hi = V.min(axis=0), V.max(axis=0)
    assert np.all(partly.features_dropped_near >= lo) and np.all(partly.features_dropped_near <= hi)
    assert kept.features_left_out == [] and len(partly.features_left_out) > 0
    lengths = [stretch["length"] for stretch in partly.features_left_out]
    assert all(length > 0 for length in lengths) and lengths == sorted(lengths, reverse=True)
    for stretch in partly.features_left_out:
        assert stretch["edges"] > 0
        assert np.all(np.array(stretch["place"]) >= lo) and np.all(np.array(stretch["place"]) <= hi)
    none = geodual.remesh(V, F, sites=500, sharp_angle=0, statistics=False)
    assert none.feature_chains == 0 and none.features_dropped_near.shape == (0, 3)
    assert none.features_left_out == []


def test_says_the_sites_added_where_the_count_cannot_carry_the_creases(data_dir):
    # OpenSCAD's functions example at 500 sites: no try keeps its creases;
    # with more sites they are kept, and the sites added are said.
    V, F = geodual.read_mesh(data_dir / "cad" / "functions.stl")
    raised = geodual.remesh(V, F, sites=500, statistics=False)
    assert raised.features_dropped_reason is None and raised.feature_chains > 0
    # doubled or quadrupled, and more where its chains crowd narrow pieces at that count
    assert raised.sites_added_for_creases >= 500
    assert raised.sites_added_for_creases == raised.report["sites_added_for_creases"]
    assert "site count 500 raised to" in raised.report["sites_added_for_creases_reason"]
    assert raised.sites >= 500 + raised.sites_added_for_creases
    V, F = geodual.read_mesh(data_dir / "fandisk.ply")
    kept = geodual.remesh(V, F, sites=2000, statistics=False)
    assert kept.sites_added_for_creases == 0
    assert kept.report["sites_added_for_creases_reason"] is None


def test_pin_creases_puts_sites_on_the_short_creases_and_keeps_them(data_dir):
    # rocker_arm's creases are too short to cut along at 2,000 sites: without
    # pins no site is on them; with pins the pinned sites are remesh vertices
    # at input vertices that end sharp edges.
    V, F = geodual.read_mesh(data_dir / "rocker_arm.ply")
    plain = geodual.remesh(V, F, sites=2000, statistics=False)
    pinned = geodual.remesh(V, F, sites=2000, pin_creases=True, statistics=False)
    assert plain.crease_pins == 0
    assert pinned.crease_pins > 20
    assert pinned.sites_added_near_features > 0
    assert len(pinned.vertices) >= 2000 + pinned.sites_added_near_features
    at_input = {tuple(v) for v in np.asarray(V, dtype=np.float64)}
    assert sum(tuple(v) in at_input for v in pinned.vertices) >= pinned.crease_pins
    assert sum(tuple(v) in at_input for v in plain.vertices) < pinned.crease_pins


def test_smoothing_moves_a_few_vertices_and_keeps_the_triangles(data_dir):
    # homer at 500 sites: the dual leaves a few angles below 30 degrees,
    # which the smoothing raises by moving vertices, never the triangles.
    V, F = geodual.read_mesh(data_dir / "homer.ply")
    plain = geodual.remesh(V, F, sites=500, smoothing_angle=0, statistics=False)
    smoothed = geodual.remesh(V, F, sites=500, statistics=False)
    assert plain.vertices_smoothed == 0
    assert smoothed.vertices_smoothed > 0
    np.testing.assert_array_equal(smoothed.faces, plain.faces)
    moved = np.any(smoothed.vertices != plain.vertices, axis=1)
    assert moved.sum() == smoothed.vertices_smoothed
    assert plain.stats["theta_min_deg"] < 30
    assert smoothed.stats["theta_min_deg"] > plain.stats["theta_min_deg"] + 3


def test_max_error_remeshes_until_the_bound_holds_or_returns_the_closest(fertility):
    V, F = fertility
    met = geodual.remesh(V, F, sites=200, max_error=2.0)
    assert met.error_bound_met is True
    assert met.stats["hausdorff_pct"] <= 2.0
    counts = [sites for sites, _ in met.error_rounds]
    distances = [distance for _, distance in met.error_rounds]
    # 200 sites stray beyond the bound on fertility; each remesh after has
    # more sites, and the one returned is the last, the first within it.
    assert len(counts) >= 2 and counts[0] == 200 and distances[0] > 2.0
    assert counts == sorted(set(counts))
    assert distances[-1] == met.stats["hausdorff_pct"] and all(d > 2.0 for d in distances[:-1])
    assert set(met.timings) == {"sample", "relax", "dual", "statistics"}

    # Stopped by max_sites: the closest remesh made, and the bound reported missed.
    missed = geodual.remesh(V, F, sites=200, max_error=0.5, max_sites=250)
    assert missed.error_bound_met is False
    assert missed.stats["hausdorff_pct"] > 0.5
    assert missed.stats["hausdorff_pct"] == min(d for _, d in missed.error_rounds)
    assert max(sites for sites, _ in missed.error_rounds) <= 250

    plain = geodual.remesh(V, F, sites=200, statistics=False)
    assert plain.error_bound_met is None and plain.error_rounds == []

    with pytest.raises(ValueError, match=r"max_error must be in \(0, 100\]"):
        geodual.remesh(V, F, sites=200, max_error=0.0)
    with pytest.raises(ValueError, match="max_sites needs max_error"):
        geodual.remesh(V, F, sites=200, max_sites=300)
    with pytest.raises(ValueError, match="max_sites must be at least 1"):
        geodual.remesh(V, F, sites=200, max_error=1.0, max_sites=0)
    with pytest.raises(geodual.UsageError, match="statistics"):
        geodual.remesh(V, F, sites=200, max_error=1.0, statistics=False)
    with pytest.raises(geodual.UsageError, match="sites"):
        geodual.remesh(V, F, sites=[0, 10, 20, 30], max_error=1.0)


def test_remesh_argument_errors(woody):
    V, F = woody
    with pytest.raises(ValueError, match="at most one of sites, edge_length and faces"):
        geodual.remesh(V, F, sites=100, faces=200)
    with pytest.raises(ValueError, match="at most one of sites, edge_length and faces"):
        geodual.remesh(V, F, sites=100, edge_length=1.0)
    with pytest.raises(TypeError, match="sites must be a count or a sequence"):
        geodual.remesh(V, F, 2000.0)
    with pytest.raises(ValueError, match="sites must be at least 1"):
        geodual.remesh(V, F, sites=0)
    with pytest.raises(ValueError, match="edge_length must be a finite number > 0"):
        geodual.remesh(V, F, edge_length=-1.0)
    with pytest.raises(ValueError, match="lloyd must be >= 0"):
        geodual.remesh(V, F, lloyd=-1)
    with pytest.raises(ValueError, match=r"continuation angle -1\.0+: must be in \[0, 180\]"):
        geodual.remesh(V, F, continuation_angle=-1.0)
    with pytest.raises(ValueError, match=r"smoothing angle 61\.0+: must be in \[0, 60\]"):
        geodual.remesh(V, F, smoothing_angle=61.0)
    with pytest.raises(ValueError, match="colors has 3 rows for 694 vertices"):
        geodual.remesh(V, F, colors=np.zeros((3, 3)))
    with pytest.raises(TypeError, match="progress must be a callable"):
        geodual.remesh(V, F, sites=100, progress=5)
    with pytest.raises(ValueError, match="V must be an n x 3 array"):
        geodual.remesh(V[:, :2], F)


def test_progress_reports_each_stage_in_order(woody):
    V, F = woody
    seen = []
    geodual.remesh(V, F, sites=200, lloyd=2, progress=lambda stage, fraction: seen.append((stage, fraction)))
    stages = [stage for stage, _ in seen]
    assert [s for i, s in enumerate(stages) if i == 0 or stages[i - 1] != s] == ["sample", "relax", "dual", "statistics"]
    assert all(0 <= fraction <= 1 for _, fraction in seen)
    assert seen[-1] == ("statistics", 1.0)


def test_progress_returning_false_cancels(woody):
    V, F = woody
    calls = []

    def stop_in_relax(stage, fraction):
        calls.append(stage)
        return stage != "relax"

    with pytest.raises(geodual.Cancelled, match="the progress callback returned False"):
        geodual.remesh(V, F, sites=200, progress=stop_in_relax)
    assert calls[-1] == "relax"  # not asked again once it said stop
    assert issubclass(geodual.Cancelled, geodual.Error)


def test_progress_raising_keyboard_interrupt_cancels(woody):
    V, F = woody

    def interrupt(stage, fraction):
        if stage == "relax" and fraction > 0:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        geodual.remesh(V, F, sites=200, progress=interrupt)
    # Any other exception the callback raises comes through as itself.
    with pytest.raises(ZeroDivisionError):
        geodual.geodesic(V, F, [0], progress=lambda stage, fraction: 1 / 0)


def test_ctrl_c_interrupts_a_running_remesh(data_dir):
    """A real SIGINT while the computation runs without the GIL and without a
    progress callable: the pipeline's own checks see it and stop."""
    V, F = geodual.read_mesh(data_dir / "bunny.ply")
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            geodual.remesh(V, F, sites=20000, lloyd=30)  # about a minute if not stopped
    finally:
        timer.cancel()


def test_help_is_useful():
    for name in ["remesh", "geodesic", "read_mesh"]:
        assert "Example" in getattr(geodual, name).__doc__, name
    assert "polylines" in geodual.voronoi.__doc__ and "colors" in geodual.write_mesh.__doc__
    assert "edge_length" in geodual.remesh.__doc__ and "progress" in geodual.remesh.__doc__
    assert issubclass(geodual.Error, RuntimeError) and issubclass(geodual.UsageError, ValueError)


def test_fitting_moves_vertices_towards_the_farthest_points_and_keeps_the_triangles(data_dir):
    # homer at 500 sites: the fitting moves the vertices that answer for the
    # input's points farthest from the remesh; the triangles stay and the
    # Hausdorff distance falls.
    V, F = geodual.read_mesh(data_dir / "homer.ply")
    plain = geodual.remesh(V, F, sites=500, fit_deviations=False)
    fitted = geodual.remesh(V, F, sites=500)
    assert plain.vertices_fitted == 0
    assert fitted.vertices_fitted > 0
    np.testing.assert_array_equal(fitted.faces, plain.faces)
    assert fitted.stats["hausdorff_pct"] < plain.stats["hausdorff_pct"]


def test_texture_size_returns_the_atlas_and_the_baked_images_as_arrays():
    # A plane coloured red along x: the texel at each atlas vertex's UV holds
    # (about) the colour of the plane where that vertex is.
    V, F = grid_plane(31)
    colors = np.column_stack([V[:, 0], np.zeros(len(V)), np.full(len(V), 0.5)])
    result = geodual.remesh(V, F, sites=150, lloyd=2, colors=colors, statistics=False, texture_size=128,
                            bake_normal=True)
    k = len(result.uvs)
    assert result.uvs.shape == (k, 2) and result.uv_vertices.shape == (k,)
    assert result.uv_faces.shape == result.faces.shape
    assert np.array_equal(result.uv_vertices[result.uv_faces], result.faces), "the atlas's triangles are the remesh's"
    assert result.tangents.shape == (k, 4) and set(np.unique(result.tangents[:, 3])) <= {-1.0, 1.0}
    assert result.base_color_texture.shape == (128, 128, 3) and result.base_color_texture.dtype == np.uint8
    assert result.normal_texture.shape == (128, 128, 3)
    # A flat input: the normal map holds the remesh's own normal, (0, 0, 1) in tangent space.
    texel = lambda image, uv: image[min(int(uv[1] * 128), 127), min(int(uv[0] * 128), 127)].astype(float)
    centroids = result.uvs[result.uv_faces].mean(axis=1)
    for uv in centroids[:20]:
        assert abs(texel(result.normal_texture, uv)[2] - 255) <= 2
    # The red channel grows with x (sRGB-encoded, so monotone, not linear).
    xs = result.vertices[result.uv_vertices[result.uv_faces]].mean(axis=1)[:, 0]
    reds = np.array([texel(result.base_color_texture, uv)[0] for uv in centroids])
    order = np.argsort(xs)
    assert np.corrcoef(xs[order], reds[order])[0, 1] > 0.95


def test_texture_size_is_checked():
    V, F = grid_plane(11)
    with pytest.raises(ValueError):
        geodual.remesh(V, F, sites=30, texture_size=10)
    with pytest.raises(ValueError):
        geodual.remesh(V, F, sites=30, bake_normal=True)
