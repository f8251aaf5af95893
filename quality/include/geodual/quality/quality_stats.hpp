#pragma once
// Quality statistics of a triangle mesh, and the distance between two meshes:
// the figures isotropic-remeshing papers and tools publish (shared/DESIGN.md,
// "Quality statistics"), so that geodual's output can be set side by side with
// theirs, and any two meshes (ours or another tool's) can be compared.
//
// Element quality, for a triangle with area A, half-perimeter p and longest
// edge h: Q = 6/sqrt(3) * A / (p * h), 1 for the equilateral triangle, 0 for a
// degenerate one. Angles are measured as atan2(|u x v|, u . v), accurate for
// tiny angles too.
//
// Feature recall: whether the candidate's edges follow the reference's sharp
// edges (creases where the normals of the two faces turn by at least an angle,
// geodual/mesh/sharp_edges.hpp), as a remesh of a machined part should.
//
// Degenerate faces (a repeated vertex index, or exactly zero area computed in
// double, the definition of analyze_mesh) have Q = 0 and angles (0, 0, 180)
// degrees: they count in Qmin (= 0), Qavg, the minimum angle (= 0), and with two
// angles below 30 degrees. They add nothing to the area or volume, are never
// sampled and are left out of the distance queries (a zero-area face is a
// segment or a point, covered by its neighbours in any sane mesh); their
// vertices are still measured if some face uses them.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace geodual::quality {

/// More samples than this would take days: refused.
inline constexpr std::int64_t max_samples_per_side = 1'000'000'000'000;
/// Points along the sharp edges beyond this (a tolerance far too small for
/// their length) are refused.
inline constexpr std::int64_t max_feature_samples = 1'000'000'000;

struct QualityOptions {
  /// Points drawn area-uniformly on each mesh for the distances, besides all
  /// of its referenced vertices. 10^6 keeps the sampling error of the Hausdorff
  /// distance well below typical remeshing deviations on meshes of up to a few
  /// million faces; 0 measures the vertices only.
  std::int64_t samples_per_side = 1'000'000;
  /// Seed of the (counter-based, platform-independent) sample generator.
  std::uint64_t seed = 1;
  /// Called on the calling thread now and then (between phases and every few
  /// thousand distance queries) with the fraction done, in [0, 1]; returning
  /// false cancels the computation (geodual::Cancelled is thrown). It changes
  /// no result.
  std::function<bool(double fraction)> progress{};

  /// Feature recall: an edge of the reference is sharp when the normals of
  /// its two faces turn by at least this many degrees (in (0, 180]); 0 leaves
  /// the feature recall out.
  double sharp_angle_deg = 60.0;
  /// A point of a sharp edge is recalled when some edge of the candidate
  /// passes within this distance, in % of the reference's bounding-box
  /// diagonal (> 0).
  double feature_tolerance_pct = 0.1;
  /// Also the recall on the long creases alone (FeatureRecall::long_recall_pct):
  /// the sharp chains at least this long, in mesh units (> 0; a remesh's
  /// spacing, such as remesh::uniform_spacing, is the usual choice); 0
  /// leaves it out.
  double long_crease_length = 0.0;
  /// Also give, per vertex of the reference, the largest distance measured
  /// at it (QualityReport::deviation_at_vertices): where a remesh needs
  /// more vertices to come closer.
  bool deviation_at_vertices = false;
};

/// Figures of one mesh alone. Percentages are in [0, 100].
struct TriangleQuality {
  std::int64_t vertices = 0;  ///< as stored, referenced or not
  std::int64_t faces = 0;
  std::int64_t degenerate_faces = 0;  ///< repeated index or zero area: Q = 0

  double q_min = 0.0;              ///< smallest Q over all faces
  double q_avg = 0.0;              ///< mean Q over all faces
  double theta_min_deg = 0.0;      ///< smallest angle of any face, degrees
  double theta_min_avg_deg = 0.0;  ///< mean over faces of each face's smallest angle, degrees
  double pct_angles_lt30 = 0.0;    ///< 100 * (angles < 30 degrees) / (3 * faces)
  /// 100 * (faces whose smallest angle is < 30 degrees) / (3 * faces), the
  /// "P30" other remeshers print (a third of the share of such faces).
  double p30 = 0.0;

  /// valence_histogram[k]: interior vertices with k neighbours. A vertex is
  /// interior when it is referenced and each of its edges has exactly two face
  /// sides (no boundary edge, no non-manifold edge). Edges are those of
  /// analyze_mesh: sides of faces joining two different indices.
  std::vector<std::int64_t> valence_histogram;
  std::int64_t interior_vertices = 0;
  /// 100 * (interior vertices of valence 6) / (interior vertices); empty when
  /// there is no interior vertex.
  std::optional<double> pct_valence6;

  // Topology, from analyze_mesh (see geodual/mesh/mesh_report.hpp).
  std::int64_t euler_characteristic = 0;
  std::optional<double> genus;  ///< only for an orientable 2-manifold
  std::int64_t components = 0;
  std::int64_t boundary_loops = 0;
  std::int64_t nonmanifold_edges = 0;

  double bbox_diagonal = 0.0;  ///< of the referenced vertices
  double area = 0.0;           ///< sum of the face areas
  /// Signed volume by the divergence theorem: the sum over faces of the signed
  /// volumes of the tetrahedra joining each face to the centre of the bounding
  /// box. For a closed mesh oriented counter-clockwise seen from outside it is
  /// the enclosed volume (negative if oriented the other way); for an open mesh
  /// it depends on that centre and has no geometric meaning.
  double volume = 0.0;
};

/// Element quality, valence and topology of one mesh. Throws geodual::Error for
/// a mesh without faces, a face index out of range or a non-finite coordinate.
TriangleQuality triangle_quality(const TriangleMesh& mesh);

/// Q of one face, 6/sqrt(3) A / (p h): 1 for the equilateral triangle, 0 for
/// a face with a repeated vertex or exactly zero area.
double face_quality(const TriangleMesh& mesh, Index face);

/// How well the candidate's edges follow the reference's sharp edges.
///
/// A sharp edge is an edge of the reference with two faces whose normals turn
/// by at least sharp_angle_deg (geodual::sharp_edges). The distance from a
/// point to the candidate is here the distance to the nearest of its edges (as
/// segments; edges are the sides of faces joining two different vertices),
/// not to its surface: a crease cut by a chamfer of triangles is not
/// recalled, however close the surface. Each sharp edge is sampled at both
/// ends and at points at most a tenth of the tolerance apart; a point is
/// recalled when its distance is at most the tolerance, and the share of each
/// piece between two samples that is recalled is taken as the mean of its
/// ends' (the trapezoid rule), so the recall is exact up to a tenth of the
/// tolerance at each place where the distance crosses the tolerance.
/// JSON names (geodual stats --json, the remesh's extras): feature_recall_edges,
/// feature_recall_length, feature_recall_pct, feature_max_gap_pct.
///
/// With QualityOptions::long_crease_length, the same share on the long
/// creases alone: the sharp edges form chains, maximal polylines of sharp
/// edges whose inner vertices have exactly two sharp edges (a chain ends
/// where one, three or more sharp edges meet, or closes as a loop); the
/// chains at least that long are the long creases.
struct FeatureRecall {
  double sharp_angle_deg = 0.0;  ///< the threshold used
  double tolerance = 0.0;        ///< feature_tolerance_pct of the diagonal, in mesh units
  std::int64_t edges = 0;        ///< sharp edges of the reference
  double length = 0.0;           ///< their total length, in mesh units
  std::int64_t samples = 0;      ///< points measured along them
  /// 100 * (length of sharp edges within the tolerance of a candidate edge) /
  /// length; 100 when the reference has no sharp edge.
  double recall_pct = 100.0;
  double max_gap = 0.0;      ///< largest distance from a sampled point of a sharp edge to the candidate's edges
  double max_gap_pct = 0.0;  ///< 100 * max_gap / the reference's bounding-box diagonal

  std::int64_t chains = 0;          ///< sharp chains of the reference
  double long_crease_length = 0.0;  ///< the threshold used; 0: the figures below were not measured
  std::int64_t long_chains = 0;     ///< chains at least long_crease_length long
  std::int64_t long_edges = 0;      ///< their sharp edges
  double long_length = 0.0;         ///< their total length, in mesh units
  /// 100 * (length of the long chains' edges within the tolerance of a
  /// candidate edge) / long_length; 100 when there is no long chain.
  double long_recall_pct = 100.0;
};

/// The candidate's quality and its distance to the reference.
///
/// Distances: each side's sample set is its referenced vertices plus
/// `samples_per_side` points drawn area-uniformly on its faces; every sample's
/// distance to the other mesh's surface is exact up to rounding (the nearest
/// of its faces of non-zero area, found through a CGAL AABB tree). Hausdorff =
/// max over both sample sets; RMS = sqrt of the mean squared distance over
/// both sample sets together (vertices included, so densely meshed regions
/// weigh a little more). Since the samples are finite, the Hausdorff figure is
/// a lower bound of the true one (exact where the farthest point is a vertex,
/// as for nested convex shapes).
/// The _pct figures are in percent of the reference's bounding-box diagonal.
///
/// Same meshes and options give the same bits whatever the number of threads.
struct QualityReport {
  TriangleQuality reference;
  TriangleQuality candidate;

  double hausdorff = 0.0;                         ///< two-sided, max of the two below
  double hausdorff_reference_to_candidate = 0.0;  ///< max over reference samples
  double hausdorff_candidate_to_reference = 0.0;  ///< max over candidate samples
  /// Where `hausdorff` is reached: the point measured (of the reference, or
  /// of the candidate where that side's maximum is larger) farthest from the
  /// other mesh; the first such point where several are.
  Eigen::Vector3d hausdorff_point = Eigen::Vector3d::Zero();
  double rms = 0.0;                    ///< over both sample sets together
  double hausdorff_pct = 0.0;          ///< 100 * hausdorff / reference.bbox_diagonal
  double rms_pct = 0.0;                ///< 100 * rms / reference.bbox_diagonal
  std::int64_t reference_samples = 0;  ///< measured points on the reference: vertices + samples
  std::int64_t candidate_samples = 0;  ///< measured points on the candidate

  double area_change_pct = 0.0;  ///< 100 * (candidate.area - reference.area) / reference.area
  /// 100 * (candidate.volume - reference.volume) / |reference.volume|; empty
  /// when the reference's volume is 0. Meaningful for closed meshes only.
  std::optional<double> volume_change_pct;

  /// Feature recall (see FeatureRecall); empty when options.sharp_angle_deg is 0.
  std::optional<FeatureRecall> features;
  /// With options.deviation_at_vertices, per vertex of the reference (0 for
  /// one no face uses), the largest of these distances: its own to the
  /// candidate, those of the reference's samples on its faces, and those of
  /// the candidate's samples and vertices whose nearest point of the
  /// reference lies on one of its faces. Their maximum is `hausdorff`.
  std::vector<double> deviation_at_vertices;
};

/// Compares `candidate` with `reference`. Throws geodual::Error (naming which
/// mesh) for what triangle_quality refuses, for a mesh whose faces all have
/// zero area, for a sample count below 0 or above max_samples_per_side, and
/// for what feature_recall refuses.
QualityReport compare_meshes(const TriangleMesh& reference, const TriangleMesh& candidate,
                             const QualityOptions& options = {});

/// The feature recall alone (compare_meshes computes it too), with
/// options.sharp_angle_deg, feature_tolerance_pct, long_crease_length and progress. Throws
/// geodual::Error (naming which mesh) for a mesh without faces, a face index
/// out of range or a non-finite coordinate, for a sharp angle outside
/// (0, 180], a tolerance that is not positive, a long-crease length that is
/// negative or not finite, and for a tolerance so small
/// that the sharp edges would need more than max_feature_samples samples.
FeatureRecall feature_recall(const TriangleMesh& reference, const TriangleMesh& candidate,
                             const QualityOptions& options = {});

}  // namespace geodual::quality
