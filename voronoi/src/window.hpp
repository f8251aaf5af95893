#pragma once
// A window (Surazhsky et al. 2005, §3.1): an interval [b0, b1] of an edge
// together with the unfolded image of the (pseudo-)source that reaches it
// through one sequence of faces. Coordinates are in the canonical frame of
// the edge (see PropagationMesh): the edge lies on the x axis from 0 to its
// length. A source below the axis (y < 0) sends the window into face [0] of
// the edge, a source above it into face [1]. The edge itself is implied by
// where the window is stored (WindowStore keeps one sorted array per edge),
// and the source's distance offset sigma and site by `source`, an index into
// the store's table of emitted sources: every window emitted at once from one
// point shares them, and so do all windows propagated from those.

#include "geodual/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace geodual::voronoi::detail {

struct Window {
  double b0 = 0, b1 = 0;
  double source_x = 0, source_y = 0;
  std::uint32_t source = 0;
  /// Waiting in the FIFO to be propagated into the face it enters.
  std::uint8_t queued = 0;

  /// Distance at abscissa x of the edge through this window, whose source
  /// has distance offset `sigma`.
  double distance_at(double x, double sigma) const {
    const double dx = x - source_x;
    return sigma + std::sqrt(dx * dx + source_y * source_y);
  }

  /// Smallest distance over [b0, b1].
  double min_distance(double sigma) const {
    const double x = std::clamp(source_x, b0, b1);
    return distance_at(x, sigma);
  }

  /// The side of the edge whose face the window enters: 0 or 1.
  int entering_side() const { return source_y < 0 ? 0 : 1; }
};

/// Where a window's paths come from: the site, and the distance from it to
/// the (pseudo-)source the window is unfolded from.
struct WindowSource {
  double sigma = 0;
  Index site = -1;
};

static_assert(sizeof(Window) == 40, "windows are packed in per-edge arrays; keep them small");

}  // namespace geodual::voronoi::detail
