#include "window_store.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace geodual::voronoi::detail {
namespace {

/// A candidate must beat an existing window by this relative margin to
/// replace it; re-derived copies of one window then never displace each other.
constexpr double kTieMargin = 1e-13;

/// f(x) = d1(x) - d2(x).
double difference(const Window& w1, const Window& w2, double x) { return w1.distance_at(x) - w2.distance_at(x); }

/// Abscissas in (lo, hi) where the two windows' distances are equal: the
/// roots of sigma1 + |x - s1| = sigma2 + |x - s2|, found by squaring twice
/// (a quadratic, whose spurious roots are harmless: every sub-interval is then
/// decided by evaluating both windows), polished with Newton steps, and backed
/// by bisection wherever the difference changes sign but no root was found.
int crossings(const Window& w1, const Window& w2, double lo, double hi, std::array<double, 2>& roots) {
  const double shift = 0.5 * (lo + hi);  // work near the interval for precision
  const double a1 = w1.source_x - shift, a2 = w2.source_x - shift;
  const double h1 = w1.source_y * w1.source_y, h2 = w2.source_y * w2.source_y;
  const double delta = w2.sigma - w1.sigma;
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
      const double f = (w1.sigma + r1) - (w2.sigma + r2);
      const double df = (r1 > 0 ? (x - w1.source_x) / r1 : 0) - (r2 > 0 ? (x - w2.source_x) / r2 : 0);
      if (df == 0) break;
      x -= f / df;
    }
    if (x > lo && x < hi && (count == 0 || x != roots[0])) roots[count++] = x;
  }
  if (count == 0) {
    double f_lo = difference(w1, w2, lo), f_hi = difference(w1, w2, hi);
    if ((f_lo < 0 && f_hi > 0) || (f_lo > 0 && f_hi < 0)) {
      double a = lo, b = hi;
      for (int i = 0; i < 60 && b - a > 0; ++i) {
        const double m = 0.5 * (a + b);
        const double f_m = difference(w1, w2, m);
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

Index WindowStore::allocate(const Window& w) {
  Index id;
  if (!free_.empty()) {
    id = free_.back();
    free_.pop_back();
    pool_[id] = w;
    queued_[id] = 0;
  } else if (!free_lists_.empty()) {
    // Take the first window of a cleared edge's list; its successor heads
    // the rest. The slot is about to be written anyway, so following the
    // list here costs nothing extra.
    id = free_lists_.back();
    const Index next = pool_[id].next;
    if (next == -1) {
      free_lists_.pop_back();
    } else {
      free_lists_.back() = next;
    }
    pool_[id] = w;
    queued_[id] = 0;
  } else {
    id = static_cast<Index>(pool_.size());
    pool_.push_back(w);
    queued_.push_back(0);
  }
  ++edge_count_[w.edge];
  peak_ = std::max(peak_, ++live_);
  return id;
}

void WindowStore::release(Index id) {
  queued_[id] = 0;
  free_.push_back(id);
  --edge_count_[pool_[id].edge];
  --live_;
}

void WindowStore::clear_edge(Index edge) {
  // The whole list becomes free at once, without walking it: allocate()
  // takes its windows one by one. None of them is queued (RWR clears only
  // edges of inactive faces, after the FIFO has run dry).
  if (head_[edge] != -1) free_lists_.push_back(head_[edge]);
  live_ -= edge_count_[edge];
  edge_count_[edge] = 0;
  head_[edge] = -1;
  edge_site_[edge] = kNoSite;
}

void WindowStore::push_segment(double lo, double hi, int owner) {
  if (hi - lo <= min_length_) return;
  if (!segments_.empty() && segments_.back().owner == owner && segments_.back().hi >= lo - min_length_) {
    segments_.back().hi = hi;  // contiguous piece of the same window
    return;
  }
  segments_.push_back({lo, hi, owner});
}

void WindowStore::split_overlap(const Window& candidate, int k, double lo, double hi) {
  const Window& existing = pool_[overlaps_[k]];
  const double f_lo = difference(candidate, existing, lo);
  const double f_hi = difference(candidate, existing, hi);
  // Each distance changes by at most |dx| along the edge, so the difference
  // is 2-Lipschitz: it cannot reach zero inside when both ends are farther
  // from zero than that allows, and one window wins the whole overlap.
  if ((f_lo > 0) == (f_hi > 0) && std::abs(f_lo) + std::abs(f_hi) > 2 * (hi - lo)) {
    const double mid = 0.5 * (lo + hi);
    const double de = existing.distance_at(mid);
    push_segment(lo, hi, candidate.distance_at(mid) < de - kTieMargin * de ? -1 : k);
    return;
  }
  std::array<double, 2> roots{};
  const int count = crossings(candidate, existing, lo, hi, roots);
  std::array<double, 4> cuts{lo, 0, 0, 0};
  int cut_count = 1;
  for (int i = 0; i < count; ++i) cuts[cut_count++] = roots[i];
  cuts[cut_count++] = hi;
  for (int i = 0; i + 1 < cut_count; ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (b <= a) continue;
    const double mid = 0.5 * (a + b);
    const double dc = candidate.distance_at(mid), de = existing.distance_at(mid);
    push_segment(a, b, dc < de - kTieMargin * de ? -1 : k);
  }
}

void WindowStore::insert(const Window& candidate, double edge_length, std::vector<Index>& created) {
  min_length_ = 1e-12 * edge_length;
  const Index edge = candidate.edge;
  Index& site_summary = edge_site_[edge];
  if (site_summary == kNoSite) {
    site_summary = candidate.site;
  } else if (site_summary != candidate.site) {
    site_summary = kMixedSites;
  }
  Index prev = -1;
  Index cur = head_[edge];
  while (cur != -1 && pool_[cur].b1 <= candidate.b0) {
    prev = cur;
    cur = pool_[cur].next;
  }
  overlaps_.clear();
  Index after = cur;
  while (after != -1 && pool_[after].b0 < candidate.b1) {
    overlaps_.push_back(after);
    after = pool_[after].next;
  }

  if (overlaps_.empty()) {
    Index id = allocate(candidate);
    pool_[id].next = after;
    (prev == -1 ? head_[edge] : pool_[prev].next) = id;
    created.push_back(id);
    return;
  }

  // The lower envelope over the union of the candidate and the overlapped
  // windows, as segments in increasing x.
  segments_.clear();
  double x = candidate.b0;
  for (int k = 0; k < static_cast<int>(overlaps_.size()); ++k) {
    const Window& existing = pool_[overlaps_[k]];
    if (existing.b0 < x) {
      push_segment(existing.b0, x, k);  // only the first can start before the candidate
    } else if (existing.b0 > x) {
      push_segment(x, existing.b0, -1);
    }
    const double lo = std::max(existing.b0, x);
    const double hi = std::min(existing.b1, candidate.b1);
    if (hi > lo) split_overlap(candidate, k, lo, hi);
    if (existing.b1 > candidate.b1) push_segment(candidate.b1, existing.b1, k);
    x = std::max(x, hi);
  }
  if (x < candidate.b1) push_segment(x, candidate.b1, -1);

  // Rebuild the list between prev and after. Each existing window keeps its id
  // for its first piece (so a queued entry still finds it); further pieces and
  // the candidate's pieces get new ids.
  Index link = prev;
  auto append = [&](Index id) {
    (link == -1 ? head_[edge] : pool_[link].next) = id;
    link = id;
  };
  constexpr std::uint8_t kUnused = 0, kUsed = 1;
  std::vector<std::uint8_t>& used = used_;  // which existing windows kept a piece
  used.assign(overlaps_.size(), kUnused);
  for (const Segment& s : segments_) {
    if (s.owner < 0) {
      Window piece = candidate;
      piece.b0 = s.lo;
      piece.b1 = s.hi;
      const Index id = allocate(piece);
      created.push_back(id);
      append(id);
      continue;
    }
    const Index original = overlaps_[s.owner];
    if (used[s.owner] == kUnused) {
      used[s.owner] = kUsed;
      pool_[original].b0 = s.lo;
      pool_[original].b1 = s.hi;
      append(original);
    } else {
      Window piece = pool_[original];
      piece.b0 = s.lo;
      piece.b1 = s.hi;
      const bool was_queued = queued_[original] != 0;
      const Index id = allocate(piece);
      if (was_queued) created.push_back(id);
      append(id);
    }
  }
  (link == -1 ? head_[edge] : pool_[link].next) = after;
  for (std::size_t k = 0; k < overlaps_.size(); ++k) {
    if (used[k] == kUnused) release(overlaps_[k]);
  }
}

}  // namespace geodual::voronoi::detail
