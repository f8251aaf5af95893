#pragma once
// The windows held on the edges: one array per edge, sorted along it and
// pairwise disjoint, such that at every point of an edge the array holds the
// smallest distance any inserted window offered there (MMP trimming,
// Surazhsky et al. 2005 §3.3).
//
// The arrays are blocks of one arena, of power-of-two capacities, so that the
// windows of an edge share one or two cache lines: propagation reads them
// together (expanding a face, trimming, redundancy checks). Freed blocks are
// reused by size class, newest first, so inserting and freeing do not
// allocate once the arena has grown.

#include "window.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {

class WindowStore {
 public:
  explicit WindowStore(Index num_edges)
      : slots_(static_cast<std::size_t>(num_edges)) {}

  static constexpr Index kNoSite = -1;
  static constexpr Index kMixedSites = -2;

  /// The windows of an edge, sorted along it. Valid until the next insert or
  /// clear on any edge (the arena may move).
  std::span<const Window> on_edge(Index edge) const {
    const Slot& s = slots_[edge];
    return {arena_.data() + s.begin, s.count};
  }
  std::span<Window> on_edge(Index edge) {
    const Slot& s = slots_[edge];
    return {arena_.data() + s.begin, s.count};
  }

  /// A surviving piece of an inserted window: its position in on_edge() and
  /// its interval (the rest is the candidate's), so that callers need not
  /// read back what was just written.
  struct Piece {
    Index position;
    double b0, b1;
  };

  /// Inserts `candidate` on `edge` keeping the edge's array the pointwise
  /// minimum. Where the candidate is not strictly better (by a relative
  /// margin) the existing windows win, so ties never churn. Appends to
  /// `created` the candidate's surviving pieces, in increasing order (their
  /// `queued` flag is cleared; pieces of existing windows keep theirs).
  void insert(Index edge, const Window& candidate, double edge_length, std::vector<Piece>& created);

  /// The site of every window ever inserted on the edge since it was last
  /// cleared, kNoSite if none, kMixedSites if several (the windows held now
  /// may still all share one site).
  Index edge_site(Index edge) const { return slots_[edge].site; }

  /// Frees every window of the edge.
  void clear_edge(Index edge);

  std::int64_t live() const { return live_; }
  std::int64_t peak() const { return peak_; }
  /// Bytes of window storage in use: the arena's extent, including blocks
  /// that are free for reuse and the unused capacity of the edges' blocks.
  std::int64_t bytes() const { return static_cast<std::int64_t>(arena_.size() * sizeof(Window)); }

 private:
  /// An edge's block and site summary, together: inserting reads both.
  struct Slot {
    std::uint32_t begin = 0;
    std::uint32_t count = 0;
    std::uint32_t capacity = 0;
    Index site = kNoSite;
  };
  struct Segment {
    double lo, hi;
    int owner;  ///< -1: the candidate; k >= 0: the k-th overlapped window
  };

  /// Makes on_edge(edge)[at .. at + removed) room for `added` windows
  /// (contents unspecified), moving the tail; returns the edge's first window.
  Window* splice(Index edge, std::uint32_t at, std::uint32_t removed, std::uint32_t added);
  std::uint32_t allocate_block(std::uint32_t capacity);
  void free_block(std::uint32_t begin, std::uint32_t capacity);
  void split_overlap(const Window& candidate, const Window& existing, int k, double lo, double hi);
  void push_segment(double lo, double hi, int owner);

  std::vector<Window> arena_;
  std::vector<Slot> slots_;
  std::array<std::vector<std::uint32_t>, 32> free_blocks_;  ///< by log2 of the capacity
  std::int64_t live_ = 0;
  std::int64_t peak_ = 0;
  // Scratch space reused by insert().
  std::vector<Segment> segments_;
  std::vector<Window> replacement_;
  double min_length_ = 0;
};

}  // namespace geodual::voronoi::detail
