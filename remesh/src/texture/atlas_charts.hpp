#pragma once
// The texture atlas's charts: faces grown into patches within a cone of
// normals, never across seams, boundaries or non-manifold edges; each patch
// cut into a surface of its own (its vertices copied where the patch meets
// itself across a seam) and tested for being a topological disk.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace geodual::remesh::detail {

/// Per face and per edge k (corners k, k + 1): the face across that edge
/// where a chart may cross it, else -1. A chart crosses only edges with
/// exactly two faces, both with an area, run in opposite directions (the
/// faces agree on orientation), and not among the seams.
using FaceNeighbours = std::vector<std::array<Index, 3>>;

FaceNeighbours chart_neighbours(const TriangleMesh& mesh, const std::vector<std::array<Index, 2>>& seams);

/// Charts grown over the faces: each one from a seed, over crossable edges,
/// taking first the face whose normal turns least from the chart's
/// area-weighted mean normal and lies nearest the seed (a weighted sum of
/// the two), while every face of the chart stays within
/// max_angle_degrees of that mean. Seeds are the faces next to earlier
/// charts, in the order they were met, else the first face left.
/// Deterministic. Each chart's faces are listed in the order they joined.
std::vector<std::vector<Index>> grow_charts(const TriangleMesh& mesh, const FaceNeighbours& neighbours,
                                            double max_angle_degrees);

/// A chart as a surface of its own: its faces' corners at one mesh vertex
/// share a chart vertex when they are joined round that vertex across edges
/// the chart crosses, so that the chart is cut open along seams inside it.
struct ChartSurface {
  std::vector<Index> faces;                   ///< mesh faces
  std::vector<std::array<Index, 3>> corners;  ///< per face, its chart vertices (the face's corner order)
  std::vector<Index> source_vertex;           ///< per chart vertex, its mesh vertex
  Index euler_characteristic = 0;
  Index boundary_loops = 0;
  /// Connected (always, for the charts built here), one boundary loop, Euler characteristic 1.
  bool is_disk() const { return euler_characteristic == 1 && boundary_loops == 1; }
};

/// \pre `faces` are connected through crossable edges. `face_slot` is
/// scratch of one entry per mesh face, all -1, and is left so.
ChartSurface chart_surface(const TriangleMesh& mesh, const FaceNeighbours& neighbours, std::vector<Index> faces,
                           std::vector<Index>& face_slot);

/// The chart's faces split in two connected parts, grown breadth first from
/// two faces far apart (by steps across crossable edges). \pre at least two
/// connected faces; `face_slot` as for chart_surface.
std::array<std::vector<Index>, 2> split_chart(const FaceNeighbours& neighbours, const std::vector<Index>& faces,
                                              std::vector<Index>& face_slot);

}  // namespace geodual::remesh::detail
