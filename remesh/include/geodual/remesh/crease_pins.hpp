#pragma once
// Sites pinned on the short creases (FeatureSet::short_creases): creases too
// short or too weak at the remesh's scale to cut along, which a remesh still
// follows when sites stay on them and their neighbours along the crease are
// joined by edges (follow_segments.hpp). The sites round a pin should be
// about as close as the nearest other pin (spacing_density.hpp), or the
// triangles between make slivers.
//
//   auto pins = crease_pins(surface, features, {.spacing = h, .max_chord_error = e});
//   auto rho = spacing_density(surface, pins.spacing, {.spacing = h});

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/spacing_density.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace geodual::remesh {

struct CreasePinOptions {
  double spacing = 0;  ///< the remesh's edge length (> 0): pins at most this far apart along a crease
  /// Every point of a crease lies within this distance of the chord between
  /// two consecutive pins (> 0); a crease this short gets one pin, and pins
  /// closer than this are one.
  double max_chord_error = 0;
  /// The sites round a pin this many times as far from it as the nearest
  /// other pin (>= 1): a little farther than the pins' own spacing, so that
  /// the two pins of a short crease are each other's nearest sites, which
  /// the dual joins by an edge.
  double neighbour_spacing = 1.5;
};

struct CreasePins {
  /// At vertices of the surface on the creases, off the chains and the boundary.
  std::vector<SurfacePoint> sites;
  /// Per pin: its position and the spacing of the sites round it:
  /// options.neighbour_spacing times the distance to the nearest other pin,
  /// at most options.spacing.
  std::vector<SpacedPoint> spacing;
  /// Pairs of pins (indices into `sites`) next to each other along a crease.
  std::vector<std::array<std::size_t, 2>> segments;
};

/// The pins on features.short_creases, detected on `surface`. Deterministic.
/// \throw UsageError for options out of range.
CreasePins crease_pins(const TriangleMesh& surface, const FeatureSet& features, const CreasePinOptions& options);
CreasePins crease_pins(const RemeshSurface& surface, const FeatureSet& features, const CreasePinOptions& options);

}  // namespace geodual::remesh
