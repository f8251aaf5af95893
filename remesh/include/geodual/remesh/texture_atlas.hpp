#pragma once
// A UV atlas for a remesh: charts cut from its faces (never across the given
// seams, e.g. its feature chains), each a topological disk parameterised by
// least-squares conformal maps (CGAL's Surface_mesh_parameterization), scaled
// to one texel density and packed into a square texture with a gutter of free
// texels round each chart, so that mip-mapping does not bleed between charts.
// See docs/algorithms.md#texture-atlas.
//
//   auto atlas = geodual::remesh::make_texture_atlas(remesh, {.texture_size = 2048});
//   atlas.uvs.row(v)  // texture coordinates of atlas vertex v (a copy of remesh vertex atlas.source_vertex[v])

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geodual::remesh {

/// Texture coordinates, one row (u, v) per vertex.
using UvMatrix = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

struct AtlasOptions {
  /// Texels per side of the square texture the atlas is packed for (at least 64).
  int texture_size = 2048;
  /// Texels kept free round every chart, and between a chart and the texture's border (at least 1).
  int gutter = 4;
  /// A chart grows over faces whose normals turn by at most this many degrees
  /// from its mean normal (in (0, 90]).
  double max_chart_angle = 60;
  /// Edges of the mesh (its vertex pairs, in either order) that no chart
  /// crosses: they become seams. Edges that are not edges of the mesh are ignored.
  std::vector<std::array<Index, 2>> seams = {};
};

/// The atlas of a mesh: the mesh's triangles on vertices copied where a seam
/// passes, each copy with its texture coordinates.
struct TextureAtlas {
  /// The mesh's triangles, in the same order, on the atlas's vertices.
  FaceMatrix faces;
  /// Per atlas vertex, the mesh vertex it is a copy of (a vertex on a seam has several copies).
  std::vector<Index> source_vertex;
  /// Per atlas vertex, glTF texture coordinates in [0, 1]: (0, 0) is the
  /// top-left corner of the image's first texel, (1, 1) the bottom-right
  /// corner of its last. A triangle keeps its orientation: counter-clockwise
  /// in 3D seen from outside is clockwise in (u, v) with v down, i.e.
  /// counter-clockwise seen as an image: in the numbers stored,
  /// (u1 - u0) (v2 - v0) - (v1 - v0) (u2 - u0) < 0 for every face. Every
  /// chart keeps `gutter` free texels round it (so two charts are at least
  /// 2 gutter texels apart) and charts do not overlap.
  UvMatrix uvs;
  /// Per face, its chart (0 .. charts - 1).
  std::vector<Index> chart_of_face;
  Index charts = 0;
  /// The share of the texture's texels whose centres lie inside a chart's triangle.
  double texture_used = 0;
  /// Area distortion per face: max(s, 1/s) - 1, where s is the face's UV area
  /// over its 3D area, divided by the same ratio for the whole atlas (0: every
  /// face has the atlas's texel density). Mean weighted by 3D area, and the largest.
  double mean_area_distortion = 0;
  double max_area_distortion = 0;
  /// Angle distortion per face, in degrees: the largest difference between a
  /// corner's angle in 3D and in UV. Mean weighted by 3D area, and the largest.
  double mean_angle_distortion = 0;
  double max_angle_distortion = 0;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const AtlasOptions& options);

/// The atlas of `mesh` (a remesh: manifold, no degenerate faces; several
/// components and boundaries are fine). Deterministic: the same mesh and
/// options give the same atlas. \throw geodual::UsageError as check_options;
/// geodual::Error where the mesh has no face or a chart cannot be flattened.
TextureAtlas make_texture_atlas(const TriangleMesh& mesh, const AtlasOptions& options = {});

}  // namespace geodual::remesh
