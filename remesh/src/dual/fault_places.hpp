#pragma once
// Where a failed repair's faults lie, for DualRepairError and its message.

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

namespace geodual::remesh {

/// The first point of each cluster of `points`, in their order: a point
/// within `spacing` of one already kept joins its cluster.
std::vector<Eigen::Vector3d> fault_places(std::span<const Eigen::Vector3d> points, double spacing);

/// "; the faults lie near (x, y, z)", or "; the faults lie at N places, near
/// a, b, c, ..." (three named at most); "" for none.
std::string fault_places_text(const std::vector<Eigen::Vector3d>& places);

}  // namespace geodual::remesh
