#include "cell_moments.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>

namespace geodual::voronoi::detail {
namespace {

Eigen::Vector3d corner(const TriangleMesh& mesh, Index face, int c) {
  return mesh.vertices.row(mesh.faces(face, c)).transpose();
}

Eigen::Vector3d face_normal(const TriangleMesh& mesh, Index face) {
  return (corner(mesh, face, 1) - corner(mesh, face, 0)).cross(corner(mesh, face, 2) - corner(mesh, face, 0));
}

}  // namespace

std::vector<Eigen::Vector3d> site_normals(const TriangleMesh& mesh, const GeodesicField& field) {
  std::vector<Eigen::Vector3d> normal(field.sites.size(), Eigen::Vector3d::UnitZ());
  std::vector<Index> vertex_site(static_cast<std::size_t>(mesh.vertices.rows()), -1);
  for (std::size_t s = 0; s < field.sites.size(); ++s) {
    const SurfacePoint& site = field.sites[s];
    if (site.kind == SurfacePoint::Kind::face) {
      normal[s] = face_normal(mesh, site.element).normalized();
    } else {
      vertex_site[site.element] = static_cast<Index>(s);
      normal[s].setZero();
    }
  }
  for (Index f = 0; f < mesh.faces.rows(); ++f) {
    if (field.face_edges[f][0] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      const Index s = vertex_site[mesh.faces(f, c)];
      if (s >= 0) normal[s] += face_normal(mesh, f);
    }
  }
  for (Eigen::Vector3d& n : normal) {
    n = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
  }
  return normal;
}

CellMoments::CellMoments(const TriangleMesh& mesh, const GeodesicField& field,
                         std::span<const Eigen::Vector3d> site_normals)
    : mesh_(mesh), field_(field), site_normal_(site_normals) {}

void CellMoments::set_face(Index face, const FaceLayout& layout) {
  face_ = face;
  layout_ = layout;
  const Eigen::Vector3d a = corner(mesh_, face, 0), b = corner(mesh_, face, 1);
  axis_x_ = b - a;
  const double length = axis_x_.norm();
  axis_x_ = length > 0 ? Eigen::Vector3d(axis_x_ / length) : Eigen::Vector3d::UnitX();
  normal_ = face_normal(mesh_, face);
  normal_ = normal_.norm() > 0 ? Eigen::Vector3d(normal_.normalized()) : axis_x_.unitOrthogonal();
  axis_y_ = normal_.cross(axis_x_);
}

template <class Distance>
CellIntegrals CellMoments::integrate(Index site, std::span<const Eigen::Vector2d> polygon,
                                     const Distance& distance) const {
  if (polygon.size() < 3) return {};
  const Eigen::Quaterniond to_site = Eigen::Quaterniond::FromTwoVectors(normal_, site_normal_[site]);
  double energy = 0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  // A fan of triangles from the first point (signed areas make it exact for
  // any simple polygon), each by the rule on its edge midpoints.
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Eigen::Vector2d &p = polygon[0], &q = polygon[i], &r = polygon[i + 1];
    const double area = 0.5 * ((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
    if (area == 0) continue;
    for (const Eigen::Vector2d& x :
         {Eigen::Vector2d(0.5 * (p + q)), Eigen::Vector2d(0.5 * (q + r)), Eigen::Vector2d(0.5 * (r + p))}) {
      Eigen::Vector2d direction;
      const double d = distance(x, direction);
      if (!std::isfinite(d)) continue;
      energy += area / 3 * d * d;
      moment += area / 3 * d * direction;
    }
  }
  const Eigen::Vector3d in_space = moment.x() * axis_x_ + moment.y() * axis_y_;
  Eigen::Vector3d at_site = to_site * in_space;
  at_site -= site_normal_[site] * site_normal_[site].dot(at_site);  // round-off out of the plane
  return {energy, at_site};
}

CellIntegrals CellMoments::polygon(Index site, std::span<const Eigen::Vector2d> polygon,
                                   const ConeEnvelope& envelope) const {
  const int slot = envelope.slot_of(site);
  if (slot < 0) return {};
  return integrate(site, polygon, [&](const Eigen::Vector2d& x, Eigen::Vector2d& direction) {
    return envelope.distance(slot, x, &direction);
  });
}

CellIntegrals CellMoments::face_from_corners(Index site) const {
  std::array<double, 3> d{};
  for (int c = 0; c < 3; ++c) d[c] = field_.distance[mesh_.faces(face_, c)];
  const auto& c = layout_.corner;
  // The point a with |c_k - a| = d_k (a straight cone from the site):
  // subtracting the k = 0 equation from k = 1, 2 leaves a 2 x 2 linear system.
  Eigen::Matrix2d system;
  Eigen::Vector2d rhs;
  for (int k = 1; k < 3; ++k) {
    system.row(k - 1) = 2 * (c[k] - c[0]).transpose();
    rhs[k - 1] = c[k].squaredNorm() - c[0].squaredNorm() - (d[k] * d[k] - d[0] * d[0]);
  }
  const Eigen::Vector2d apex = system.fullPivLu().solve(rhs);
  const double scale = std::max({d[0], d[1], d[2], (c[1] - c[0]).norm()});
  bool fits = apex.allFinite();
  for (int k = 0; k < 3 && fits; ++k) fits = std::abs((c[k] - apex).norm() - d[k]) <= 1e-9 * scale;
  const std::array<Eigen::Vector2d, 3> triangle = {c[0], c[1], c[2]};
  if (fits) {
    return integrate(site, triangle, [&](const Eigen::Vector2d& x, Eigen::Vector2d& direction) {
      const Eigen::Vector2d r = x - apex;
      const double length = r.norm();
      direction = length > 0 ? Eigen::Vector2d(r / length) : Eigen::Vector2d::Zero();
      return length;
    });
  }
  // Behind a pseudo-source: distances interpolated linearly, direction along
  // their gradient.
  const double twice_area = (c[1] - c[0]).x() * (c[2] - c[0]).y() - (c[1] - c[0]).y() * (c[2] - c[0]).x();
  if (!(twice_area > 0)) return {};
  const Eigen::Vector2d gradient = (d[0] * Eigen::Vector2d(c[1].y() - c[2].y(), c[2].x() - c[1].x()) +
                                    d[1] * Eigen::Vector2d(c[2].y() - c[0].y(), c[0].x() - c[2].x()) +
                                    d[2] * Eigen::Vector2d(c[0].y() - c[1].y(), c[1].x() - c[0].x())) /
                                   twice_area;
  const Eigen::Vector2d unit = gradient.norm() > 0 ? Eigen::Vector2d(gradient.normalized()) : Eigen::Vector2d::Zero();
  return integrate(site, triangle, [&](const Eigen::Vector2d& x, Eigen::Vector2d& direction) {
    direction = unit;
    const Eigen::Vector3d b = layout_.barycentric(x);
    return b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
  });
}

}  // namespace geodual::voronoi::detail
