#pragma once
// The windows held on the edges: one array per edge, sorted along it and
// pairwise disjoint, such that at every point of an edge the array holds the
// smallest distance any inserted window offered there (MMP trimming,
// Surazhsky et al. 2005 §3.3).
//
// The arrays are blocks of a few capacities (1, 2, 3, 4, 6, 8, 12, ...: two
// per octave, so that a block is on average ~85% full), so that the windows
// of an edge share one or two cache lines: propagation reads them together
// (expanding a face, trimming, redundancy checks). Blocks are carved from
// fixed-size pages, so that the store grows a page at a time and never
// copies or over-allocates as one growing array would (at its peak that held
// the old and the new array, three times the windows' bytes). Freed blocks,
// and page ends too short for the next block, are reused by capacity,
// newest first, so inserting and freeing do not allocate once the pages are
// there. Edges grow from one class to the next and RWR frees whole edges,
// so the free blocks pile up in the small classes; once they hold 1/8 of
// the pages and a new page is due, the blocks are packed together instead.

#include "window.hpp"
#include "zeroed_array.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {

class WindowStore {
 public:
  /// With `release_memory`, a repack hands the heap's free pages back (see
  /// GeodesicOptions::release_memory_between_phases).
  explicit WindowStore(Index num_edges, bool release_memory = true);

  static constexpr Index kNoSite = -1;
  static constexpr Index kMixedSites = -2;

  /// The windows of an edge, sorted along it. Valid until the next insert on
  /// or clear of the same edge.
  std::span<const Window> on_edge(Index edge) const {
    const Slot& s = slots_[edge];
    return {window_at(s.begin), s.count};
  }
  std::span<Window> on_edge(Index edge) {
    const Slot& s = slots_[edge];
    return {window_at(s.begin), s.count};
  }

  /// Registers the source of windows about to be inserted; they carry the
  /// returned id in Window::source.
  std::uint32_t add_source(double sigma, Index site);
  std::size_t num_sources() const { return sources_.size(); }
  void reserve_sources(std::size_t count) { sources_.reserve(count); }
  /// Forgets the sources (no window may refer to them any more).
  void clear_sources() { sources_.clear(); }
  const WindowSource& source(std::uint32_t id) const { return sources_[id]; }
  const WindowSource& source_of(const Window& w) const { return sources_[w.source]; }
  void prefetch_source([[maybe_unused]] const Window& w) const {
#if defined(__GNUC__)
    __builtin_prefetch(sources_.data() + w.source);
#endif
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
  /// `source` is source_of(candidate), which the caller has at hand.
  void insert(Index edge, const Window& candidate, const WindowSource& source, double edge_length,
              std::vector<Piece>& created);

  /// The site of every window ever inserted on the edge since it was last
  /// cleared, kNoSite if none, kMixedSites if several (the windows held now
  /// may still all share one site).
  Index edge_site(Index edge) const { return ~slots_[edge].not_site; }

  /// Frees every window of the edge (its mark stays).
  void clear_edge(Index edge);

  /// One bit per edge for the caller, kept with the edge's windows (window-VTP
  /// marks the edges waiting in its FIFO); false at first.
  bool marked(Index edge) const { return slots_[edge].marked != 0; }
  void set_marked(Index edge, bool marked) { slots_[edge].marked = marked ? 1 : 0; }

  /// The edges that hold windows, increasing.
  std::vector<Index> edges_with_windows();

  /// Packs the windows together in memory and gives back the pages left
  /// empty: once propagation is over, when the free blocks and unused
  /// capacity would otherwise add half as much again. The store stays
  /// usable; an edge that grows afterwards moves to a new block.
  void compact();

  /// Moves the windows out for good: calls take(edge, windows) for every
  /// edge that holds windows, in increasing edge order, and gives the pages
  /// back as it goes, so that the caller's copy and the store never hold the
  /// windows twice. The edges go in `rounds` ranges of about equal numbers
  /// of windows; after each, the windows left slide down to the front of the
  /// pages and the pages emptied behind them are unmapped (moving
  /// (rounds - 1) / 2 times the windows' bytes in all). The store is empty
  /// afterwards; the table of sources stays.
  void drain(const std::function<void(Index, std::span<const Window>)>& take, int rounds);

  std::int64_t live() const { return live_; }
  /// Times the blocks were packed together to make room (see allocate_block).
  std::int64_t repacks() const { return repacks_; }
  std::int64_t peak() const { return peak_; }
  /// Bytes of window storage held: every page, including blocks that are
  /// free for reuse and the unused capacity of the edges' blocks.
  /// The table of sources counts too.
  std::int64_t bytes() const {
    return held_pages_ * kPageWindows * static_cast<std::int64_t>(sizeof(Window)) +
           static_cast<std::int64_t>(sources_.capacity() * sizeof(WindowSource));
  }

 private:
  /// Windows are addressed by a 32-bit number: page (high bits) and
  /// position in the page (low bits).
  static constexpr int kPageShift = 12;
  static constexpr std::uint32_t kPageWindows = std::uint32_t{1} << kPageShift;

  Window* window_at(std::uint32_t address) const {
    return page_of_[address >> kPageShift] + (address & (kPageWindows - 1));
  }

  /// Block capacities by class: 0 is no block, then 1, 2, 3, 4, 6, 8, 12, ...
  static constexpr std::uint32_t kNoBlock = 0;
  static constexpr int kClasses = 64;
  static std::uint32_t block_size(std::uint32_t block_class) {
    if (block_class < 2) return block_class;
    return ((block_class & 1) ? 3u : 2u) << ((block_class - 2) / 2);
  }
  /// The smallest class that holds `count` > 0 windows.
  static std::uint32_t class_for(std::uint32_t count);

  /// An edge's block and site summary, together (12 bytes): inserting reads
  /// both. All-zero bytes are an empty slot (see slots_).
  static constexpr std::uint32_t kMaxCount = (std::uint32_t{1} << 24) - 1;
  struct Slot {
    std::uint32_t begin = 0;
    std::uint32_t count : 24 = 0;
    std::uint32_t block_class : 7 = kNoBlock;
    std::uint32_t marked : 1 = 0;  ///< see marked()
    Index not_site = ~kNoSite;     ///< edge_site(), bitwise negated: 0 is kNoSite
  };
  static_assert(kNoBlock == 0 && ~kNoSite == 0, "an all-zero Slot is an empty one");
  static_assert(kClasses <= 128, "block classes fit in Slot::block_class");
  struct Segment {
    double lo, hi;
    int owner;  ///< -1: the candidate; k >= 0: the k-th overlapped window
  };

  /// Makes on_edge(edge)[at .. at + removed) room for `added` windows
  /// (contents unspecified), moving the tail; returns the edge's first window.
  Window* splice(Index edge, std::uint32_t at, std::uint32_t removed, std::uint32_t added);
  /// A block of the class's capacity.
  std::uint32_t allocate_block(std::uint32_t block_class);
  /// Moves next_free_ to where a block of `size` can be carved from the pages
  /// held, handing the page ends it skips to the free lists; false if none.
  bool carve(std::uint32_t size);
  /// Hands what is left after next_free_ to the free lists.
  void free_rest_of_pages();
  /// Slides the blocks together, dropping the free ones (see allocate_block).
  void repack();
  /// The edges that hold windows, or a block (possibly emptied), by address.
  enum class Holding { windows, a_block };
  std::vector<Index> edges_by_address(Holding holding);
  /// Sorts block_edges_ by edge, without repeats or edges that hold no block.
  void tidy_block_edges();
  /// Slides the blocks of `edges` (in memory order; every edge holding
  /// windows) down to the front of the pages, exactly full, and unmaps the
  /// pages left empty.
  void slide_down(std::span<const Index> edges);
  static std::uint32_t capacity(const Slot& slot);
  void free_block(std::uint32_t begin, std::uint32_t block_class);
  /// Hands the unused [from, to) of one allocation to the free lists.
  void free_range(std::uint32_t from, std::uint32_t to);
  /// Adds pages for a block of `size` windows from the next page boundary on:
  /// one page, or, for a block larger than a page, contiguous pages of its own.
  void add_pages(std::uint32_t size);
  void split_overlap(const Window& candidate, double candidate_sigma, const Window& existing, double existing_sigma,
                     int k, double lo, double hi);
  void push_segment(double lo, double hi, int owner);

  /// Pages are mapped from the operating system directly, not taken from
  /// malloc's heap: they are most of the memory and come and go all through
  /// propagation, and in the heap, between the arrays growing beside them,
  /// they left it fragmented (tens of MB of resident memory more than live).
  struct PageRelease {
    std::size_t bytes = 0;
    void operator()(Window* pages) const;
  };
  using PageMemory = std::unique_ptr<Window[], PageRelease>;
  static PageMemory map_pages(std::size_t windows);

  std::vector<PageMemory> allocations_;               ///< a page, or the pages of one large block
  std::vector<std::uint32_t> allocation_first_page_;  ///< of each allocation
  std::vector<Window*> page_of_;                      ///< by page number; null once given back
  std::int64_t held_pages_ = 0;
  std::uint32_t next_free_ = 0;    ///< unused from here to the end of the pages
  std::int64_t free_windows_ = 0;  ///< capacity of the free blocks
  /// Repack rather than add a page once the free blocks hold 1/kRepackFraction of the pages.
  static constexpr std::int64_t kRepackFraction = 16;
  std::int64_t repacks_ = 0;
  bool release_memory_ = true;
  /// Zeroed pages: a propagation that reaches part of the mesh (one group
  /// of sites) makes only that part's slots resident.
  ZeroedArray<Slot> slots_;
  /// Every edge that holds a block (and some that held one since the last
  /// tidy_block_edges), so that walks over the edges holding windows read
  /// only their slots: reading the others would make their pages resident
  /// too (where the kernel gives each page read its own zeroed page).
  std::vector<Index> block_edges_;
  std::size_t tidy_block_edges_size_ = 0;  ///< block_edges_.size() after the last tidy
  std::vector<WindowSource> sources_;
  std::array<std::vector<std::uint32_t>, kClasses> free_blocks_;  ///< by class
  std::int64_t live_ = 0;
  std::int64_t peak_ = 0;
  // Scratch space reused by insert().
  std::vector<Segment> segments_;
  std::vector<Window> replacement_;
  double min_length_ = 0;
};

}  // namespace geodual::voronoi::detail
