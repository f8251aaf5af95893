#pragma once
// The vertex queue of window-VTP: at most one entry per vertex and kind
// (expand: the vertex's faces join the traversed area; emit: a pseudo-source
// sends its windows), keyed by distance. An indexed 4-ary heap whose keys only
// decrease in place, so it holds no stale duplicates: its top is always the
// true smallest pending key, which RWR needs as its lower bound.

#include "geodual/mesh/triangle_mesh.hpp"
#include "zeroed_array.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual::voronoi::detail {

enum class EventKind : std::uint8_t { expand = 0, emit = 1 };

struct Event {
  double key = 0;
  Index vertex = -1;
  EventKind kind = EventKind::expand;

  /// Total order: by key, then expand before emit, then by vertex.
  bool before(const Event& o) const {
    if (key != o.key) return key < o.key;
    if (kind != o.kind) return kind < o.kind;
    return vertex < o.vertex;
  }
};

class EventQueue {
 public:
  /// Reserves room for every entry at once: address space costs no memory
  /// until used, whereas a doubling array leaves its outgrown copies behind.
  explicit EventQueue(Index num_vertices) : position_(2 * static_cast<std::size_t>(num_vertices)) {
    heap_.reserve(position_.size());
  }

  bool empty() const { return heap_.empty(); }
  const Event& top() const { return heap_.front(); }

  /// Inserts the event, or lowers the key of the vertex's pending event of the
  /// same kind (a key that is not lower is ignored).
  void push_or_decrease(const Event& event) {
    const std::uint32_t position = position_[slot_index(event)];
    std::size_t slot = heap_.size();
    if (position == kAbsent) {
      heap_.push_back(event);
    } else {
      slot = position - 1;
      if (!(event.key < heap_[slot].key)) return;
      heap_[slot].key = event.key;
    }
    sift_up(slot);
  }

  void pop() {
    position_[slot_index(heap_.front())] = kAbsent;
    const Event last = heap_.back();
    heap_.pop_back();
    if (heap_.empty()) return;
    heap_.front() = last;
    position_[slot_index(last)] = 1;
    sift_down(0);
  }

 private:
  static constexpr std::uint32_t kAbsent = 0;
  static constexpr std::size_t kArity = 4;

  static std::size_t slot_index(const Event& e) {
    return 2 * static_cast<std::size_t>(e.vertex) + static_cast<std::size_t>(e.kind);
  }

  void place(std::size_t i, const Event& e) {
    heap_[i] = e;
    position_[slot_index(e)] = static_cast<std::uint32_t>(i + 1);
  }

  void sift_up(std::size_t i) {
    const Event e = heap_[i];
    while (i > 0) {
      const std::size_t parent = (i - 1) / kArity;
      if (!e.before(heap_[parent])) break;
      place(i, heap_[parent]);
      i = parent;
    }
    place(i, e);
  }

  void sift_down(std::size_t i) {
    const Event e = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      const std::size_t first = kArity * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + kArity < n ? first + kArity : n;
      for (std::size_t c = first + 1; c < end; ++c) {
        if (heap_[c].before(heap_[best])) best = c;
      }
      if (!heap_[best].before(e)) break;
      place(i, heap_[best]);
      i = best;
    }
    place(i, e);
  }

  std::vector<Event> heap_;
  /// Per vertex and kind: index in heap_ plus one, or kAbsent (0). Zeroed
  /// pages: a propagation that reaches part of the mesh makes only that
  /// part resident.
  ZeroedArray<std::uint32_t> position_;
};

}  // namespace geodual::voronoi::detail
