#pragma once
// A map from non-negative indices (faces, edges) to small values, by open
// addressing: for the few elements of a large mesh that a computation
// touches scattered over the numbering, where a per-element array would be
// resident whole.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace geodual {

/// Linear probing, at most half full; iteration order is never exposed, so
/// results built on it do not depend on the hashing.
template <class Value>
class IndexHashMap {
  static_assert(std::is_trivially_copyable_v<Value>);

 public:
  /// Empties the map, keeping its capacity.
  void clear() {
    for (Slot& slot : slots_) slot.key = kEmpty;
    size_ = 0;
  }
  std::size_t size() const { return size_; }

  /// Adds key -> value; false (and nothing changed) if key was there.
  /// \pre key >= 0
  bool insert(Index key, const Value& value) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    return place(key, value);
  }
  /// As a set: adds key; false if it was there.
  bool insert(Index key) { return insert(key, Value{}); }
  /// The value of key, or nullptr.
  const Value* find(Index key) const {
    if (slots_.empty()) return nullptr;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t at = home(key, mask);; at = (at + 1) & mask) {
      if (slots_[at].key == key) return &slots_[at].value;
      if (slots_[at].key == kEmpty) return nullptr;
    }
  }

 private:
  static constexpr Index kEmpty = -1;
  struct Slot {
    Index key = kEmpty;
    Value value{};
  };
  /// Fibonacci hashing: the top bits of key times 2^64 / phi.
  static std::size_t home(Index key, std::size_t mask) {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> 32) & mask;
  }
  bool place(Index key, const Value& value) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t at = home(key, mask);; at = (at + 1) & mask) {
      if (slots_[at].key == key) return false;
      if (slots_[at].key == kEmpty) {
        slots_[at] = {key, value};
        ++size_;
        return true;
      }
    }
  }
  void grow() {
    std::vector<Slot> old(slots_.empty() ? 64 : 2 * slots_.size());
    std::swap(old, slots_);
    size_ = 0;
    for (const Slot& slot : old) {
      if (slot.key != kEmpty) place(slot.key, slot.value);
    }
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
};

/// A set of indices (see IndexHashMap).
struct NoValue {};
using IndexHashSet = IndexHashMap<NoValue>;

}  // namespace geodual
