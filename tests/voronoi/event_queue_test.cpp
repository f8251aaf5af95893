// The vertex queue of window-VTP: one entry per vertex and kind, keys only
// lowered in place, popped in the order Event::before defines. Its positions
// start as zeroed pages (0: absent), so the first entry of each slot and the
// entry at heap position 0 are the cases to get right.

#include "../../voronoi/src/event_queue.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace geodual::voronoi::detail {
namespace {

std::vector<Event> pop_all(EventQueue& queue) {
  std::vector<Event> popped;
  while (!queue.empty()) {
    popped.push_back(queue.top());
    queue.pop();
  }
  return popped;
}

TEST(EventQueue, PopsByKeyThenKindThenVertexAndLowersKeysInPlace) {
  EventQueue queue(5);
  EXPECT_TRUE(queue.empty());
  queue.push_or_decrease({3.0, 0, EventKind::expand});  // at heap position 0 first
  queue.push_or_decrease({2.0, 4, EventKind::emit});
  queue.push_or_decrease({2.0, 4, EventKind::expand});  // same vertex, other kind: its own entry
  queue.push_or_decrease({5.0, 1, EventKind::expand});
  queue.push_or_decrease({4.0, 1, EventKind::expand});  // lowers vertex 1's key
  queue.push_or_decrease({6.0, 0, EventKind::expand});  // higher: ignored
  queue.push_or_decrease({1.0, 0, EventKind::expand});  // lowers the entry at the top
  const std::vector<Event> popped = pop_all(queue);
  ASSERT_EQ(popped.size(), 4u);
  EXPECT_EQ(popped[0].vertex, 0);
  EXPECT_EQ(popped[0].key, 1.0);
  EXPECT_EQ(popped[1].vertex, 4);
  EXPECT_EQ(popped[1].kind, EventKind::expand);
  EXPECT_EQ(popped[2].vertex, 4);
  EXPECT_EQ(popped[2].kind, EventKind::emit);
  EXPECT_EQ(popped[3].vertex, 1);
  EXPECT_EQ(popped[3].key, 4.0);
  // Popped entries are absent again: pushing one anew (at any key) adds it.
  queue.push_or_decrease({9.0, 0, EventKind::expand});
  queue.push_or_decrease({8.0, 4, EventKind::emit});
  const std::vector<Event> again = pop_all(queue);
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(again[0].vertex, 4);
  EXPECT_EQ(again[1].vertex, 0);
  EXPECT_EQ(again[1].key, 9.0);
}

}  // namespace
}  // namespace geodual::voronoi::detail
