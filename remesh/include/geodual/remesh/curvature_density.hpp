#pragma once
// A curvature-adapted density for the weighted CVT (lloyd.hpp): where the
// surface bends sharply at the scale of the remesh's edges, more sites.
//
//   auto rho = geodual::remesh::curvature_density(mesh, {.strength = 1, .spacing = h});
//   LloydOptions lloyd;  lloyd.density = rho;  // one value per mesh vertex
//
// A weighted CVT of energy sum_i int_cell rho(x) d(x, s_i)^2 dA spaces its
// sites like rho^(-1/4) in 2D (Gersho's conjecture, Du, Faber & Gunzburger,
// SIAM Review 1999, §2.3). A uniform mesh of spacing h misses a surface of
// curvature k by its chord error, about h^2 k / 8; equal error everywhere
// would need h ~ k^(-1/2), i.e. rho ~ k^2. The density blends the two:
//
//   rho = min(max_ratio, 1 + strength (spacing * k)^2),
//
// uniform where the surface is flat at the scale `spacing` (the uniform
// mesh's edge length), equalising the chord error where it is not, and never
// more than `max_ratio` (spacing at least max_ratio^(-1/4) of the flat one).
//
// k per vertex is the total absolute curvature |k1| + |k2| of the discrete
// surface, from the dihedral angles: (sum over its edges of |angle| length) /
// (2 * its third of the incident face area) (Cohen-Steiner & Morvan 2003;
// exact on average for cylinders and spheres, and it sees creases). A scan's
// k is noisy and concentrated on creases, so it is averaged over about one
// `spacing` (area-weighted one-ring averages, (spacing / mean edge)^2
// passes, a diffusion over that length) before the formula, and rho again
// after it, so that the density changes over a cell or more (the weighted
// Lloyd step assumes rho nearly linear across a cell) and the sizes grade
// smoothly.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <vector>

namespace geodual::remesh {

struct CurvatureDensityOptions {
  /// 0: uniform density (all ones).
  double strength = 1.0;
  /// The spacing of the uniform mesh (its mean edge length); sets both the
  /// scale of "sharp" and the smoothing length. Must be > 0.
  double spacing = 0;
  /// Largest density (>= 1).
  double max_ratio = 16.0;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const CurvatureDensityOptions& options);

/// One density per mesh vertex (1 for vertices no face uses). Faces with a
/// repeated vertex index are ignored; edges of more than two faces count as
/// flat. Throws geodual::UsageError for options out of range.
std::vector<double> curvature_density(const TriangleMesh& mesh, const CurvatureDensityOptions& options);

/// The mean edge length of a uniform remesh of `mesh` with `sites` vertices:
/// sqrt(2 A / (sqrt(3) sites)), A the mesh's area (2 * sites equilateral
/// triangles of that edge cover it).
double uniform_spacing(const TriangleMesh& mesh, std::int64_t sites);

}  // namespace geodual::remesh
