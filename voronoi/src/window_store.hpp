#pragma once
// The windows held on the edges: one list per edge, sorted along it and
// pairwise disjoint, such that at every point of an edge the list holds the
// smallest distance any inserted window offered there (MMP trimming,
// Surazhsky et al. 2005 §3.3). Windows live in one pool with a free list, so
// inserting and freeing do not allocate once the pool has grown.

#include "window.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual::voronoi::detail {

class WindowStore {
 public:
  explicit WindowStore(Index num_edges)
      : head_(static_cast<std::size_t>(num_edges), -1),
        edge_site_(static_cast<std::size_t>(num_edges), kNoSite),
        edge_count_(static_cast<std::size_t>(num_edges), 0) {}

  static constexpr Index kNoSite = -1;
  static constexpr Index kMixedSites = -2;

  Index head(Index edge) const { return head_[edge]; }
  const Window& operator[](Index id) const { return pool_[id]; }

  bool queued(Index id) const { return queued_[id] != 0; }
  void set_queued(Index id, bool queued) { queued_[id] = queued; }

  /// Inserts `candidate` (whose `edge` is set) keeping the edge's list the
  /// pointwise minimum. Where the candidate is not strictly better (by a
  /// relative margin) the existing windows win, so ties never churn. Appends
  /// to `created` the ids of the candidate's surviving pieces and of pieces
  /// split off queued windows (which must be queued too).
  void insert(const Window& candidate, double edge_length, std::vector<Index>& created);

  /// The site of every window ever inserted on the edge since it was last
  /// cleared, kNoSite if none, kMixedSites if several (the windows held now
  /// may still all share one site).
  Index edge_site(Index edge) const { return edge_site_[edge]; }

  /// Frees every window of the edge.
  void clear_edge(Index edge);

  std::int64_t live() const { return live_; }
  std::int64_t peak() const { return peak_; }

 private:
  struct Segment {
    double lo, hi;
    int owner;  ///< -1: the candidate; k >= 0: overlaps_[k]
  };

  Index allocate(const Window& w);
  void release(Index id);
  void split_overlap(const Window& candidate, int k, double lo, double hi);
  void push_segment(double lo, double hi, int owner);

  std::vector<Window> pool_;
  std::vector<std::uint8_t> queued_;
  std::vector<Index> free_;        ///< single free windows
  std::vector<Index> free_lists_;  ///< heads of whole freed edge lists
  std::vector<Index> head_;
  std::vector<Index> edge_site_;
  std::vector<Index> edge_count_;  ///< windows held per edge
  std::int64_t live_ = 0;
  std::int64_t peak_ = 0;
  // Scratch space reused by insert().
  std::vector<Index> overlaps_;
  std::vector<Segment> segments_;
  std::vector<std::uint8_t> used_;
  double min_length_ = 0;
};

}  // namespace geodual::voronoi::detail
