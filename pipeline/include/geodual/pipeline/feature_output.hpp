#pragma once
// The sharp features a remesh kept, for its pictures and coloured outputs
// (`geodual remesh --color features`).

#include "geodual/mesh/vertex_attributes.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"

#include <Eigen/Core>

#include <vector>

namespace geodual::pipeline {

/// Per vertex of result.remesh.mesh: red where it lies on a feature chain
/// the remesh kept (result.features) or is a pin on a short crease
/// (crease_pin_vertices), light grey elsewhere (everywhere when there are
/// none); sRGB-encoded as VertexAttributes::colors.
ColorMatrix feature_colors(const RemeshPipelineResult& result);

/// The chains the remesh kept, then the short creases it pinned, each a
/// polyline of positions on the input surface (for a preview's lines).
std::vector<std::vector<Eigen::Vector3d>> feature_polylines(const RemeshPipelineResult& result);

}  // namespace geodual::pipeline
