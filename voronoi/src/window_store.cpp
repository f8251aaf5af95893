#include "window_store.hpp"

#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <numeric>

#if defined(__unix__)
#include <sys/mman.h>
#endif

namespace geodual::voronoi::detail {
namespace {

/// A candidate must beat an existing window by this relative margin to
/// replace it; re-derived copies of one window then never displace each other.
constexpr double kTieMargin = 1e-13;

/// A window with its source's sigma, for the comparisons below.
struct Cone {
  const Window& w;
  double sigma;
  double distance_at(double x) const { return w.distance_at(x, sigma); }
};

/// f(x) = d1(x) - d2(x).
double difference(const Cone& c1, const Cone& c2, double x) { return c1.distance_at(x) - c2.distance_at(x); }

/// Abscissas in (lo, hi) where the two windows' distances are equal: the
/// roots of sigma1 + |x - s1| = sigma2 + |x - s2|, found by squaring twice
/// (a quadratic, whose spurious roots are harmless: every sub-interval is then
/// decided by evaluating both windows), polished with Newton steps, and backed
/// by bisection wherever the difference changes sign but no root was found.
int crossings(const Cone& c1, const Cone& c2, double lo, double hi, std::array<double, 2>& roots) {
  const Window &w1 = c1.w, &w2 = c2.w;
  const double shift = 0.5 * (lo + hi);  // work near the interval for precision
  const double a1 = w1.source_x - shift, a2 = w2.source_x - shift;
  const double h1 = w1.source_y * w1.source_y, h2 = w2.source_y * w2.source_y;
  const double delta = c2.sigma - c1.sigma;
  const double alpha = 2 * (a2 - a1);
  const double beta = a1 * a1 - a2 * a2 + h1 - h2 - delta * delta;
  const double d2 = 4 * delta * delta;
  const double qa = alpha * alpha - d2;
  const double qb = 2 * alpha * beta + 2 * d2 * a2;
  const double qc = beta * beta - d2 * (a2 * a2 + h2);

  std::array<double, 2> candidates{};
  int found = 0;
  const double scale = std::max({std::abs(qb), std::abs(qc), 1e-300});
  if (std::abs(qa) <= 1e-14 * scale) {
    if (qb != 0) candidates[found++] = -qc / qb;
  } else {
    double disc = qb * qb - 4 * qa * qc;
    // Equal sigmas give a double root whose discriminant rounds either way.
    if (disc < 0 && disc > -1e-10 * (qb * qb + std::abs(4 * qa * qc))) disc = 0;
    if (disc >= 0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      if (q != 0) {
        candidates[found++] = q / qa;
        candidates[found++] = qc / q;
      } else {
        candidates[found++] = -qb / (2 * qa);
      }
    }
  }
  int count = 0;
  for (int i = 0; i < found; ++i) {
    double x = candidates[i] + shift;
    if (!std::isfinite(x)) continue;
    for (int step = 0; step < 2; ++step) {
      const double r1 = std::sqrt((x - w1.source_x) * (x - w1.source_x) + h1);
      const double r2 = std::sqrt((x - w2.source_x) * (x - w2.source_x) + h2);
      const double f = (c1.sigma + r1) - (c2.sigma + r2);
      const double df = (r1 > 0 ? (x - w1.source_x) / r1 : 0) - (r2 > 0 ? (x - w2.source_x) / r2 : 0);
      if (df == 0) break;
      x -= f / df;
    }
    if (x > lo && x < hi && (count == 0 || x != roots[0])) roots[count++] = x;
  }
  if (count == 0) {
    double f_lo = difference(c1, c2, lo), f_hi = difference(c1, c2, hi);
    if ((f_lo < 0 && f_hi > 0) || (f_lo > 0 && f_hi < 0)) {
      double a = lo, b = hi;
      for (int i = 0; i < 60 && b - a > 0; ++i) {
        const double m = 0.5 * (a + b);
        const double f_m = difference(c1, c2, m);
        if ((f_m < 0) == (f_lo < 0)) {
          a = m;
          f_lo = f_m;
        } else {
          b = m;
        }
      }
      roots[count++] = 0.5 * (a + b);
    }
  }
  if (count == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  return count;
}

}  // namespace

WindowStore::WindowStore(Index num_edges, bool release_memory)
    : release_memory_(release_memory), slots_(static_cast<std::size_t>(num_edges)) {
  // Address 0, where empty edges point, always exists.
  add_pages(kPageWindows);
}

std::uint32_t WindowStore::add_source(double sigma, Index site) {
  if (sources_.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw Error("geodesic propagation needs more than 2^32 window sources");
  }
  sources_.push_back({sigma, site});
  return static_cast<std::uint32_t>(sources_.size() - 1);
}

std::uint32_t WindowStore::class_for(std::uint32_t count) {
  if (count <= 2) return count;
  // 2^(b-1) < count <= 2^b: the class of 1.5 * 2^(b-1) or of 2^b.
  const auto b = static_cast<std::uint32_t>(std::bit_width(count - 1));
  const std::uint32_t half = std::uint32_t{1} << (b - 1);
  return count <= half + half / 2 ? 2 * b - 1 : 2 * b;
}

WindowStore::PageMemory WindowStore::map_pages(std::size_t windows) {
  const std::size_t bytes = windows * sizeof(Window);
#if defined(__unix__)
  void* memory = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw std::bad_alloc();
  // Windows are implicit-lifetime aggregates; every one is written before it is read.
  return PageMemory(static_cast<Window*>(memory), PageRelease{bytes});
#else
  return PageMemory(new Window[windows], PageRelease{bytes});
#endif
}

void WindowStore::PageRelease::operator()(Window* pages) const {
#if defined(__unix__)
  munmap(pages, bytes);
#else
  delete[] pages;
#endif
}

void WindowStore::add_pages(std::uint32_t size) {
  const std::uint64_t pages = (std::uint64_t{size} + kPageWindows - 1) >> kPageShift;
  if ((static_cast<std::uint64_t>(page_of_.size()) + pages) << kPageShift > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("geodesic propagation needs more than 2^32 windows at once");
  }
  allocations_.push_back(map_pages(pages << kPageShift));
  allocation_first_page_.push_back(static_cast<std::uint32_t>(page_of_.size()));
  for (std::uint64_t p = 0; p < pages; ++p) page_of_.push_back(allocations_.back().get() + (p << kPageShift));
  held_pages_ += static_cast<std::int64_t>(pages);
}

void WindowStore::free_range(std::uint32_t from, std::uint32_t to) {
  while (from < to) {
    // The largest class that fits.
    std::uint32_t block_class = class_for(to - from);
    if (block_size(block_class) > to - from) --block_class;
    free_block(from, block_class);
    from += block_size(block_class);
  }
}

std::uint32_t WindowStore::allocate_block(std::uint32_t block_class) {
  std::vector<std::uint32_t>& free = free_blocks_[block_class];
  if (!free.empty()) {
    const std::uint32_t begin = free.back();
    free.pop_back();
    free_windows_ -= block_size(block_class);
    return begin;
  }
  const std::uint32_t size = block_size(block_class);
  if (!carve(size)) {
    // The pages are full. Where the free blocks hold a good part of them, in
    // the wrong sizes, packing the blocks together makes room instead.
    if (free_windows_ >= held_pages_ * (kPageWindows / kRepackFraction)) {
      repack();
      ++repacks_;
      if (release_memory_) trim_heap();  // the sorted list of blocks
    }
    if (!carve(size)) {
      free_rest_of_pages();
      const auto pages_end = static_cast<std::uint32_t>(page_of_.size() << kPageShift);
      add_pages(size);
      next_free_ = pages_end;
      carve(size);
    }
  }
  const std::uint32_t begin = next_free_;
  next_free_ += size;
  return begin;
}

bool WindowStore::carve(std::uint32_t size) {
  // A block never straddles two pages (two allocations, maybe), except a
  // block larger than a page, which always gets new pages of its own.
  const auto pages_end = static_cast<std::uint32_t>(page_of_.size() << kPageShift);
  if (size > kPageWindows) return false;
  while (next_free_ < pages_end) {
    const std::uint32_t page_end = (next_free_ | (kPageWindows - 1)) + 1;
    const bool held = page_of_[next_free_ >> kPageShift] != nullptr;
    if (held && size <= page_end - next_free_) return true;
    if (held) free_range(next_free_, page_end);
    next_free_ = page_end;
  }
  return false;
}

void WindowStore::free_rest_of_pages() {
  const auto pages_end = static_cast<std::uint32_t>(page_of_.size() << kPageShift);
  while (next_free_ < pages_end) {
    const std::uint32_t page_end = (next_free_ | (kPageWindows - 1)) + 1;
    if (page_of_[next_free_ >> kPageShift] != nullptr) free_range(next_free_, page_end);
    next_free_ = page_end;
  }
}

void WindowStore::free_block(std::uint32_t begin, std::uint32_t block_class) {
  if (block_class == kNoBlock) return;
  free_blocks_[block_class].push_back(begin);
  free_windows_ += block_size(block_class);
}

std::uint32_t WindowStore::capacity(const Slot& slot) {
  return slot.block_class != kNoBlock ? block_size(slot.block_class) : slot.count;
}

void WindowStore::repack() {
  // Every block, in the order they lie in memory, slides down to the first
  // address after the previous one where it fits in one page (so never onto
  // windows not yet moved), keeping its capacity; a block larger than a page
  // stays in its pages. The free blocks are gone; what follows the last
  // block is carved anew.
  std::uint32_t cursor = 0;
  for (const Index e : edges_by_address(Holding::a_block)) {
    Slot& slot = slots_[e];
    const std::uint32_t begin = slot.begin;
    const std::uint32_t size = capacity(slot);
    if (size > kPageWindows) {
      cursor = begin;
    } else {
      while ((cursor & (kPageWindows - 1)) + size > kPageWindows || page_of_[cursor >> kPageShift] == nullptr) {
        cursor = (cursor | (kPageWindows - 1)) + 1;
      }
    }
    if (cursor != begin && slot.count > 0)
      std::memmove(window_at(cursor), window_at(begin), slot.count * sizeof(Window));
    slot.begin = cursor;
    cursor += size;
  }
  for (std::vector<std::uint32_t>& free : free_blocks_) free.clear();
  free_windows_ = 0;
  next_free_ = cursor;
}

void WindowStore::clear_edge(Index edge) {
  Slot& slot = slots_[edge];
  live_ -= slot.count;
  free_block(slot.begin, slot.block_class);
  const bool marked = slot.marked != 0;
  slot = Slot{};
  slot.marked = marked ? 1 : 0;
}

void WindowStore::tidy_block_edges() {
  std::sort(block_edges_.begin(), block_edges_.end());
  block_edges_.erase(std::unique(block_edges_.begin(), block_edges_.end()), block_edges_.end());
  std::erase_if(block_edges_, [&](Index e) { return capacity(slots_[e]) == 0; });
  tidy_block_edges_size_ = block_edges_.size();
}

std::vector<Index> WindowStore::edges_with_windows() {
  tidy_block_edges();
  std::vector<Index> edges;
  for (const Index e : block_edges_) {
    if (slots_[e].count > 0) edges.push_back(e);
  }
  return edges;
}

std::vector<Index> WindowStore::edges_by_address(Holding holding) {
  auto holds = [&](const Slot& slot) { return holding == Holding::windows ? slot.count > 0 : capacity(slot) > 0; };
  tidy_block_edges();
  // By page first (a counting sort), then by address within each page: this
  // runs when memory is tightest, so the list is sized once, and sorting
  // small runs of plain keys is several times faster than one sort of all
  // the edges by their slots' addresses.
  std::vector<Index> page_first(page_of_.size() + 1, 0);
  for (const Index e : block_edges_) {
    if (holds(slots_[e])) ++page_first[(slots_[e].begin >> kPageShift) + 1];
  }
  std::partial_sum(page_first.begin(), page_first.end(), page_first.begin());
  std::vector<Index> edges(static_cast<std::size_t>(page_first.back()));
  {
    std::vector<Index> fill(page_first.begin(), page_first.end() - 1);
    for (const Index e : block_edges_) {
      if (holds(slots_[e])) edges[fill[slots_[e].begin >> kPageShift]++] = e;
    }
  }
  std::vector<std::uint64_t> keyed;  // address, then edge
  for (std::size_t page = 0; page + 1 < page_first.size(); ++page) {
    const auto first = edges.begin() + page_first[page], last = edges.begin() + page_first[page + 1];
    if (last - first < 2) continue;
    keyed.clear();
    for (auto it = first; it != last; ++it) {
      keyed.push_back(std::uint64_t{slots_[*it].begin} << 32 | static_cast<std::uint32_t>(*it));
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < keyed.size(); ++i)
      first[static_cast<std::ptrdiff_t>(i)] = static_cast<Index>(keyed[i] & 0xffffffffu);
  }
  return edges;
}

void WindowStore::slide_down(std::span<const Index> edges) {
  // Blocks in the order they lie in memory, each moved down to the first
  // free address in a held page it fits in whole (so never onto windows not
  // yet moved, nor into a page given back by an earlier slide: a block larger
  // than a page leaves such a gap below it). A block larger than a page stays
  // where it is, in its own pages. The block's own page is held, so the
  // cursor never passes it.
  std::vector<std::uint8_t> page_used(page_of_.size(), 0);
  std::uint32_t cursor = 0;
  for (const Index e : edges) {
    Slot& slot = slots_[e];
    const std::uint32_t count = slot.count;
    if (count > kPageWindows) {
      cursor = slot.begin;
    } else {
      while ((cursor & (kPageWindows - 1)) + count > kPageWindows || page_of_[cursor >> kPageShift] == nullptr) {
        cursor = (cursor | (kPageWindows - 1)) + 1;
      }
    }
    if (cursor != slot.begin) std::memmove(window_at(cursor), window_at(slot.begin), count * sizeof(Window));
    slot.begin = cursor;
    slot.block_class = kNoBlock;  // exactly full: growing moves it, freeing keeps nothing
    for (std::uint32_t page = cursor >> kPageShift; page <= (cursor + count - 1) >> kPageShift; ++page)
      page_used[page] = 1;
    cursor += count;
  }
  // Allocations none of whose pages hold windows any more go back.
  for (std::size_t a = 0; a < allocations_.size(); ++a) {
    if (!allocations_[a]) continue;
    const std::uint32_t first = allocation_first_page_[a];
    const std::uint32_t end =
        a + 1 < allocations_.size() ? allocation_first_page_[a + 1] : static_cast<std::uint32_t>(page_of_.size());
    if (std::any_of(page_used.begin() + first, page_used.begin() + end, [](std::uint8_t used) { return used != 0; })) {
      continue;
    }
    allocations_[a].reset();
    for (std::uint32_t page = first; page < end; ++page) page_of_[page] = nullptr;
    held_pages_ -= end - first;
  }
  for (std::vector<std::uint32_t>& free : free_blocks_) free = std::vector<std::uint32_t>();
  free_windows_ = 0;
  next_free_ = static_cast<std::uint32_t>(page_of_.size() << kPageShift);  // new blocks on new pages
}

void WindowStore::compact() { slide_down(edges_by_address(Holding::windows)); }

void WindowStore::drain(const std::function<void(Index, std::span<const Window>)>& take, int rounds) {
  std::vector<Index> left = edges_by_address(Holding::windows);
  const std::int64_t total = live_;
  std::int64_t taken = 0;
  Index next_edge = 0;
  for (int round = 1; round <= rounds && !left.empty(); ++round) {
    // Edges from next_edge on, until this round's share of the windows is taken.
    const std::int64_t goal = round == rounds ? total : total * round / rounds;
    Index end_edge = next_edge;
    for (; end_edge < static_cast<Index>(slots_.size()) && taken < goal; ++end_edge) {
      Slot& slot = slots_[end_edge];
      if (slot.count == 0) continue;
      take(end_edge, on_edge(end_edge));
      taken += slot.count;
      live_ -= slot.count;
      slot = Slot{};
    }
    next_edge = end_edge;
    std::erase_if(left, [&](Index e) { return e < end_edge; });
    slide_down(left);
  }
}

Window* WindowStore::splice(Index edge, std::uint32_t at, std::uint32_t removed, std::uint32_t added) {
  Slot& slot = slots_[edge];
  const std::uint32_t old_count = slot.count;
  const std::uint32_t count = old_count - removed + added;
  const std::uint32_t tail = old_count - at - removed;
  if (count <= block_size(slot.block_class)) {
    Window* w = window_at(slot.begin);
    if (added != removed && tail > 0) std::memmove(w + at + added, w + at + removed, tail * sizeof(Window));
  } else {
    if (count > kMaxCount) throw Error("geodesic propagation needs more than 2^24 windows on one edge");
    const bool first_block = capacity(slot) == 0;
    const std::uint32_t block_class = class_for(count);
    const std::uint32_t begin = allocate_block(block_class);
    const Window* from = window_at(slot.begin);
    Window* to = window_at(begin);
    std::copy(from, from + at, to);
    std::copy(from + at + removed, from + at + removed + tail, to + at + added);
    free_block(slot.begin, slot.block_class);
    slot.begin = begin;
    slot.block_class = block_class & 0x7f;  // < kClasses
    if (first_block) {
      block_edges_.push_back(edge);
      if (block_edges_.size() > 2 * tidy_block_edges_size_ + 4096) tidy_block_edges();  // edges freed and refilled
    }
  }
  live_ += static_cast<std::int64_t>(count) - old_count;
  peak_ = std::max(peak_, live_);
  slot.count = count & kMaxCount;
  return window_at(slot.begin);
}

void WindowStore::push_segment(double lo, double hi, int owner) {
  if (hi - lo <= min_length_) return;
  if (!segments_.empty() && segments_.back().owner == owner && segments_.back().hi >= lo - min_length_) {
    segments_.back().hi = hi;  // contiguous piece of the same window
    return;
  }
  segments_.push_back({lo, hi, owner});
}

void WindowStore::split_overlap(const Window& candidate, double candidate_sigma, const Window& existing,
                                double existing_sigma, int k, double lo, double hi) {
  // Both distances and their slopes at the ends of the overlap. Each slope
  // (x - source_x) / r grows along the edge, so the difference's slope lies
  // in [slope_lo, slope_hi]; with its end values that bounds the difference
  // over the whole overlap. Where it cannot reach zero, one window wins the
  // whole overlap (the candidate only by the tie margin, as below).
  const double dx_c_lo = lo - candidate.source_x, dx_c_hi = hi - candidate.source_x;
  const double dx_e_lo = lo - existing.source_x, dx_e_hi = hi - existing.source_x;
  const double h_c = candidate.source_y * candidate.source_y, h_e = existing.source_y * existing.source_y;
  const double r_c_lo = std::sqrt(dx_c_lo * dx_c_lo + h_c), r_c_hi = std::sqrt(dx_c_hi * dx_c_hi + h_c);
  const double r_e_lo = std::sqrt(dx_e_lo * dx_e_lo + h_e), r_e_hi = std::sqrt(dx_e_hi * dx_e_hi + h_e);
  const double d_e_lo = existing_sigma + r_e_lo, d_e_hi = existing_sigma + r_e_hi;
  const double f_lo = (candidate_sigma + r_c_lo) - d_e_lo;
  const double f_hi = (candidate_sigma + r_c_hi) - d_e_hi;
  const double slope_lo = dx_c_lo / r_c_lo - dx_e_hi / r_e_hi;
  const double slope_hi = dx_c_hi / r_c_hi - dx_e_lo / r_e_lo;
  if (f_lo > 0 && f_hi > 0) {
    // The difference stays above both lines f_lo + slope_lo (x - lo) and
    // f_hi + slope_hi (x - hi); the lowest point of the higher one bounds it.
    double floor = std::min(f_lo, f_hi);
    if (slope_lo >= 0) {
      floor = f_lo;
    } else if (slope_hi <= 0) {
      floor = f_hi;
    } else {
      const double x = std::clamp((f_hi - f_lo + slope_lo * lo - slope_hi * hi) / (slope_lo - slope_hi), lo, hi);
      floor = std::max(f_lo + slope_lo * (x - lo), f_hi + slope_hi * (x - hi));
    }
    if (floor > 0) {
      push_segment(lo, hi, k);
      return;
    }
  } else if (f_lo < 0 && f_hi < 0) {
    // Likewise from above, with the slopes exchanged.
    double ceiling = std::max(f_lo, f_hi);
    if (slope_hi <= 0) {
      ceiling = f_lo;
    } else if (slope_lo >= 0) {
      ceiling = f_hi;
    } else {
      const double x = std::clamp((f_hi - f_lo + slope_hi * lo - slope_lo * hi) / (slope_hi - slope_lo), lo, hi);
      ceiling = std::min(f_lo + slope_hi * (x - lo), f_hi + slope_lo * (x - hi));
    }
    if (ceiling < -kTieMargin * std::max(d_e_lo, d_e_hi)) {
      push_segment(lo, hi, -1);
      return;
    }
  }
  std::array<double, 2> roots{};
  const Cone c{candidate, candidate_sigma}, e{existing, existing_sigma};
  const int count = crossings(c, e, lo, hi, roots);
  std::array<double, 4> cuts{lo, 0, 0, 0};
  int cut_count = 1;
  for (int i = 0; i < count; ++i) cuts[cut_count++] = roots[i];
  cuts[cut_count++] = hi;
  for (int i = 0; i + 1 < cut_count; ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (b <= a) continue;
    const double mid = 0.5 * (a + b);
    const double dc = c.distance_at(mid), de = e.distance_at(mid);
    push_segment(a, b, dc < de - kTieMargin * de ? -1 : k);
  }
}

void WindowStore::insert(Index edge, const Window& candidate, const WindowSource& candidate_source, double edge_length,
                         std::vector<Piece>& created) {
  min_length_ = 1e-12 * edge_length;
  Index& not_site = slots_[edge].not_site;  // the site summary, negated (see Slot)
  if (not_site == ~kNoSite) {
    not_site = ~candidate_source.site;
  } else if (not_site != ~candidate_source.site) {
    not_site = ~kMixedSites;
  }
  const std::span<const Window> windows = on_edge(edge);
  const auto n = static_cast<std::uint32_t>(windows.size());
  // The windows overlapping the candidate: [first, last).
  std::uint32_t first = 0;
  while (first < n && windows[first].b1 <= candidate.b0) ++first;
  std::uint32_t last = first;
  while (last < n && windows[last].b0 < candidate.b1) ++last;

  if (first == last) {
    Window* w = splice(edge, first, 0, 1);
    w[first] = candidate;
    w[first].queued = 0;
    created.push_back({static_cast<Index>(first), candidate.b0, candidate.b1});
    return;
  }

  // The lower envelope over the union of the candidate and the overlapped
  // windows, as segments in increasing x.
  segments_.clear();
  double x = candidate.b0;
  for (std::uint32_t i = first; i < last; ++i) {
    const Window& existing = windows[i];
    const int k = static_cast<int>(i - first);
    if (existing.b0 < x) {
      push_segment(existing.b0, x, k);  // only the first can start before the candidate
    } else if (existing.b0 > x) {
      push_segment(x, existing.b0, -1);
    }
    const double lo = std::max(existing.b0, x);
    const double hi = std::min(existing.b1, candidate.b1);
    if (hi > lo) split_overlap(candidate, candidate_source.sigma, existing, sources_[existing.source].sigma, k, lo, hi);
    if (existing.b1 > candidate.b1) push_segment(candidate.b1, existing.b1, k);
    x = std::max(x, hi);
  }
  if (x < candidate.b1) push_segment(x, candidate.b1, -1);

  // The pieces replace the overlapped windows; pieces of an existing window
  // keep its data, including whether it waits to be propagated.
  replacement_.clear();
  for (const Segment& s : segments_) {
    Window piece = s.owner < 0 ? candidate : windows[first + static_cast<std::uint32_t>(s.owner)];
    piece.b0 = s.lo;
    piece.b1 = s.hi;
    if (s.owner < 0) {
      piece.queued = 0;
      created.push_back({static_cast<Index>(first + replacement_.size()), s.lo, s.hi});
    }
    replacement_.push_back(piece);
  }
  Window* w = splice(edge, first, last - first, static_cast<std::uint32_t>(replacement_.size()));
  std::copy(replacement_.begin(), replacement_.end(), w + first);
}

}  // namespace geodual::voronoi::detail
