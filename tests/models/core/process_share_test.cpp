// Tests of models/core/process_share: groups dealt out cyclically and gathered back, checked with
// parts that run on threads of this process (a stand-in for MPI ranks) against the computation
// on one part.
#include "models/core/process_share.hpp"

#include <gtest/gtest.h>

#include <barrier>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

namespace pkmopt {
namespace {

// `parts` threads gather through one board; all_gather is collective, as MPI_Allgatherv is.
class Board {
 public:
  explicit Board(int parts)
      : parts_(parts), blocks_(static_cast<std::size_t>(parts)), sync_(parts) {}
  std::vector<std::vector<char>> gather(int part, std::span<const char> mine) {
    blocks_[static_cast<std::size_t>(part)].assign(mine.begin(), mine.end());
    sync_.arrive_and_wait();
    std::vector<std::vector<char>> all = blocks_;
    sync_.arrive_and_wait();
    return all;
  }
  int parts() const { return parts_; }

 private:
  int parts_;
  std::vector<std::vector<char>> blocks_;
  std::barrier<> sync_;
};

class ThreadShare final : public ProcessShare {
 public:
  ThreadShare(Board& board, int part) : board_(board), part_(part) {}
  int parts() const override { return board_.parts(); }
  int part() const override { return part_; }
  std::vector<std::vector<char>> all_gather(std::span<const char> mine) const override {
    return board_.gather(part_, mine);
  }

 private:
  Board& board_;
  int part_;
};

struct Item {
  double value;
  int index;
};

// Items 0..n-1 in groups of `group` items; each part computes the groups it owns.
std::vector<Item> compute(const ProcessShare* share, std::size_t groups, std::size_t group) {
  std::vector<Item> items(groups * group, Item{-1.0, -1});
  for (std::size_t g = 0; g < groups; ++g) {
    if (!owns(share, g)) continue;
    for (std::size_t k = 0; k < group; ++k) {
      const std::size_t i = g * group + k;
      items[i] = {std::sin(static_cast<double>(i)), static_cast<int>(i)};
    }
  }
  share_groups(share, items.data(), groups, group * sizeof(Item));
  return items;
}

TEST(ProcessShare, EveryPartEndsWithTheResultOfOnePart) {
  for (int parts : {1, 2, 3, 5}) {
    for (std::size_t groups : {0u, 1u, 4u, 97u}) {
      for (std::size_t group : {1u, 7u}) {
        const std::vector<Item> alone = compute(nullptr, groups, group);
        Board board(parts);
        std::vector<std::vector<Item>> results(static_cast<std::size_t>(parts));
        std::vector<std::thread> threads;
        for (int p = 0; p < parts; ++p)
          threads.emplace_back([&, p] {
            const ThreadShare share(board, p);
            results[static_cast<std::size_t>(p)] = compute(&share, groups, group);
          });
        for (std::thread& t : threads) t.join();
        for (const std::vector<Item>& r : results) {
          ASSERT_EQ(r.size(), alone.size());
          for (std::size_t i = 0; i < r.size(); ++i) {
            EXPECT_EQ(r[i].index, alone[i].index) << parts << " parts, item " << i;
            EXPECT_EQ(r[i].value, alone[i].value);
          }
        }
      }
    }
  }
}

TEST(ProcessShare, GroupsAreDealtOutCyclically) {
  Board board(3);
  const ThreadShare second(board, 1);
  EXPECT_FALSE(owns(&second, 0));
  EXPECT_TRUE(owns(&second, 1));
  EXPECT_FALSE(owns(&second, 3));
  EXPECT_TRUE(owns(&second, 4));
  EXPECT_TRUE(owns(nullptr, 5));
}

// A part that sends fewer groups than it owns (a bug in a caller) is an error, not garbage.
class ShortShare final : public ProcessShare {
 public:
  int parts() const override { return 2; }
  int part() const override { return 0; }
  std::vector<std::vector<char>> all_gather(std::span<const char> mine) const override {
    return {std::vector<char>(mine.begin(), mine.end()), std::vector<char>()};
  }
};

TEST(ProcessShare, AMissingGroupIsALogicError) {
  const ShortShare share;
  std::vector<double> data(6, 1.0);
  EXPECT_THROW(share_groups(&share, data.data(), 6, sizeof(double)), std::logic_error);
}

}  // namespace
}  // namespace pkmopt
