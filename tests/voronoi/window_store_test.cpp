// WindowStore's memory moves: compact() gives back the pages it empties, and
// drain() then slides the windows left down again, past those pages. An edge
// holding more windows than a page keeps pages of its own, so pages below it
// are given back while windows remain above it; once that edge is drained,
// the windows above must slide into held pages only.

#include "../../voronoi/src/window_store.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {
namespace {

constexpr std::uint32_t kPageWindows = 4096;  // WindowStore's page, in windows

/// Appends `count` disjoint unit windows to `edge`, the i-th at [i, i + 1),
/// all from one source whose site is the edge's number (so every window says
/// which edge it came from).
void fill_edge(WindowStore& store, Index edge, std::uint32_t count) {
  const WindowSource source{0.0, edge};
  const std::uint32_t id = store.add_source(source.sigma, source.site);
  std::vector<WindowStore::Piece> created;
  for (std::uint32_t i = 0; i < count; ++i) {
    Window w;
    w.b0 = i;
    w.b1 = i + 1.0;
    w.source_x = i + 0.5;
    w.source_y = -1.0;
    w.source = id;
    created.clear();
    store.insert(edge, w, source, static_cast<double>(count), created);
  }
}

/// Checks that `windows`, drained from `edge`, are the `count` windows fill_edge put there.
void expect_filled(const WindowStore& store, Index edge, std::span<const Window> windows, std::uint32_t count) {
  ASSERT_EQ(windows.size(), count) << "edge " << edge;
  for (std::uint32_t i = 0; i < count; ++i) {
    ASSERT_EQ(windows[i].b0, static_cast<double>(i)) << "edge " << edge;
    ASSERT_EQ(store.source_of(windows[i]).site, edge) << "window " << i;
  }
}

TEST(WindowStore, DrainAfterCompactSlidesPastPagesGivenBack) {
  // Edges 1 .. kBelow hold one window each, in the first page; edge 0 then
  // grows past a page (its outgrown blocks fill pages that compact() gives
  // back, below its own pages); edges above kBelow hold one window each,
  // after edge 0's pages.
  constexpr Index kBelow = 3000, kAbove = 3000;
  constexpr std::uint32_t kLarge = kPageWindows + kPageWindows / 4;
  const Index num_edges = 1 + kBelow + kAbove;
  WindowStore store(num_edges);
  for (Index e = 1; e <= kBelow; ++e) fill_edge(store, e, 1);
  fill_edge(store, 0, kLarge);
  for (Index e = kBelow + 1; e < num_edges; ++e) fill_edge(store, e, 1);
  ASSERT_EQ(store.live(), kLarge + kBelow + kAbove);

  store.compact();
  // Two rounds: the first takes edge 0 and some of the edges below it, and
  // the edges above it slide down beyond the first page, where compact()
  // gave the pages back.
  Index expected_edge = 0;
  store.drain(
      [&](Index edge, std::span<const Window> windows) {
        ASSERT_EQ(edge, expected_edge);
        expect_filled(store, edge, windows, edge == 0 ? kLarge : 1);
        ++expected_edge;
      },
      2);
  EXPECT_EQ(expected_edge, num_edges);
  EXPECT_EQ(store.live(), 0);
}

TEST(WindowStore, CompactKeepsEveryEdgesWindows) {
  // Edges cleared in between leave free blocks; compact() packs the rest and
  // the store stays usable: an edge grows afterwards and every edge reads back.
  constexpr Index kEdges = 4000;
  WindowStore store(kEdges);
  for (Index e = 0; e < kEdges; ++e) fill_edge(store, e, 1 + static_cast<std::uint32_t>(e % 7));
  fill_edge(store, 1, kPageWindows + 100);  // replaces edge 1's windows by a block of pages of its own
  for (Index e = 2; e < kEdges; e += 3) store.clear_edge(e);
  store.compact();
  fill_edge(store, 5, 20);
  for (Index e = 0; e < kEdges; ++e) {
    const std::uint32_t count = e == 1       ? kPageWindows + 100
                                : e == 5     ? 20
                                : e % 3 == 2 ? 0
                                             : 1 + static_cast<std::uint32_t>(e % 7);
    expect_filled(store, e, store.on_edge(e), count);
  }
}

TEST(WindowStore, EdgesWithWindowsAreExactlyThoseHoldingSome) {
  // The store keeps a list of the edges given blocks, so that walks over the
  // edges holding windows read no other edge's slot. Scattered edges of a
  // large mesh are filled, some cleared, some cleared and filled again (more
  // times than the list's tidying lets it grow unchecked); the list must
  // name each edge holding windows once, in increasing order, and compact()
  // and drain() walking it must keep and give every window.
  constexpr Index kEdges = 1'000'000;
  WindowStore store(kEdges);
  std::vector<std::uint32_t> expected(kEdges, 0);
  auto fill = [&](Index e, std::uint32_t count) {
    fill_edge(store, e, count);
    expected[static_cast<std::size_t>(e)] = count;
  };
  for (Index e = 7; e < kEdges; e += 997) fill(e, 1 + static_cast<std::uint32_t>(e % 5));
  for (Index e = 7; e < kEdges; e += 3 * 997) {
    store.clear_edge(e);
    expected[static_cast<std::size_t>(e)] = 0;
  }
  for (int round = 0; round < 12; ++round) {  // 12 x 1000 refills: past the 4096 the list grows untidied
    for (Index e = 11 + round; e < kEdges; e += 1000) {
      store.clear_edge(e);
      fill(e, 2);
    }
  }
  std::vector<Index> holding;
  for (Index e = 0; e < kEdges; ++e) {
    if (expected[static_cast<std::size_t>(e)] > 0) holding.push_back(e);
  }
  EXPECT_EQ(store.edges_with_windows(), holding);
  store.compact();
  EXPECT_EQ(store.edges_with_windows(), holding);
  std::size_t taken = 0;
  store.drain(
      [&](Index edge, std::span<const Window> windows) {
        ASSERT_LT(taken, holding.size());
        ASSERT_EQ(edge, holding[taken]);
        ASSERT_EQ(windows.size(), expected[static_cast<std::size_t>(edge)]) << "edge " << edge;
        ++taken;
      },
      2);
  EXPECT_EQ(taken, holding.size());
  EXPECT_TRUE(store.edges_with_windows().empty());
}

TEST(WindowStore, EdgeSiteSummarisesTheSitesInsertedSinceCleared) {
  // The slots start as zeroed pages: an edge never touched, and one cleared,
  // must read as holding no site, and the marks must start false.
  WindowStore store(3);
  for (Index e = 0; e < 3; ++e) {
    EXPECT_EQ(store.edge_site(e), WindowStore::kNoSite);
    EXPECT_FALSE(store.marked(e));
    EXPECT_TRUE(store.on_edge(e).empty());
  }
  fill_edge(store, 1, 2);  // site 1
  EXPECT_EQ(store.edge_site(1), 1);
  EXPECT_EQ(store.edge_site(0), WindowStore::kNoSite);
  // Site 0, beyond edge 1's windows (each fill_edge window is one unit long).
  const std::uint32_t id = store.add_source(0.0, 0);
  Window w;
  w.b0 = 2;
  w.b1 = 3;
  w.source_x = 2.5;
  w.source_y = -1;
  w.source = id;
  std::vector<WindowStore::Piece> created;
  store.insert(1, w, {0.0, 0}, 3.0, created);
  EXPECT_EQ(store.edge_site(1), WindowStore::kMixedSites);
  store.set_marked(1, true);
  store.clear_edge(1);
  EXPECT_EQ(store.edge_site(1), WindowStore::kNoSite);
  EXPECT_TRUE(store.marked(1));  // the mark stays
  EXPECT_TRUE(store.on_edge(1).empty());
}

}  // namespace
}  // namespace geodual::voronoi::detail
