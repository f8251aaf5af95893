#pragma once
// Turns a stream of corner positions into indexed vertices, merging
// corners at exactly the same position (STL stores every triangle's corners on
// their own). Vertices keep the order of their first occurrence. An
// open-addressing hash table over the coordinates' bit patterns: no
// allocation per corner, linear in the number of corners.

#include "geodual/mesh/triangle_mesh.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual {

class PositionWelder {
 public:
  /// `expected_corners` sizes the table; it grows as needed.
  explicit PositionWelder(std::size_t expected_corners = 0) {
    std::size_t capacity = 64;
    while (capacity < expected_corners / 2) {
      capacity *= 2;
    }
    slots_.assign(capacity, empty_slot);
    coordinates_.reserve(3 * (expected_corners / 4));
  }

  /// The index of the vertex at (x, y, z), added if this position is new.
  /// 0.0 and -0.0 are the same position (NaNs merge only bit for bit; read_mesh rejects them).
  Index weld(double x, double y, double z) {
    ++corners_;
    const Position p{x + 0.0, y + 0.0, z + 0.0};  // + 0.0 turns -0.0 into 0.0
    std::size_t slot = hash(p) & (slots_.size() - 1);
    while (slots_[slot] != empty_slot) {
      if (equal(slots_[slot], p)) {
        return slots_[slot];
      }
      slot = (slot + 1) & (slots_.size() - 1);
    }
    const auto vertex = static_cast<Index>(coordinates_.size() / 3);
    coordinates_.insert(coordinates_.end(), {p.x, p.y, p.z});
    slots_[slot] = vertex;
    if (2 * coordinates_.size() / 3 > slots_.size()) {
      grow();
    }
    return vertex;
  }

  std::size_t vertex_count() const { return coordinates_.size() / 3; }
  /// Every weld() call: the corners read.
  std::size_t corner_count() const { return corners_; }
  /// Corners seen minus vertices made: how many corners joined an earlier vertex.
  std::int64_t welded_corners() const {
    return static_cast<std::int64_t>(corners_) - static_cast<std::int64_t>(vertex_count());
  }

  VertexMatrix vertices() const {
    return Eigen::Map<const VertexMatrix>(coordinates_.data(), static_cast<Eigen::Index>(vertex_count()), 3);
  }

 private:
  struct Position {
    double x, y, z;
  };
  static constexpr Index empty_slot = -1;

  static std::uint64_t mix(std::uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return h;
  }

  static std::size_t hash(const Position& p) {
    std::uint64_t h = mix(std::bit_cast<std::uint64_t>(p.x));
    h = mix(h ^ std::bit_cast<std::uint64_t>(p.y));
    h = mix(h ^ std::bit_cast<std::uint64_t>(p.z));
    return static_cast<std::size_t>(h);
  }

  /// Bitwise equality: exact positions (zeros were normalised on the way in).
  bool equal(Index vertex, const Position& p) const {
    const double* q = coordinates_.data() + 3 * static_cast<std::size_t>(vertex);
    return std::bit_cast<std::uint64_t>(q[0]) == std::bit_cast<std::uint64_t>(p.x) &&
           std::bit_cast<std::uint64_t>(q[1]) == std::bit_cast<std::uint64_t>(p.y) &&
           std::bit_cast<std::uint64_t>(q[2]) == std::bit_cast<std::uint64_t>(p.z);
  }

  void grow() {
    std::vector<Index> bigger(2 * slots_.size(), empty_slot);
    const std::size_t mask = bigger.size() - 1;
    for (std::size_t v = 0; v < vertex_count(); ++v) {
      const double* q = coordinates_.data() + 3 * v;
      std::size_t slot = hash(Position{q[0], q[1], q[2]}) & mask;
      while (bigger[slot] != empty_slot) {
        slot = (slot + 1) & mask;
      }
      bigger[slot] = static_cast<Index>(v);
    }
    slots_.swap(bigger);
  }

  std::vector<double> coordinates_;
  std::vector<Index> slots_;
  std::size_t corners_ = 0;
};

}  // namespace geodual
