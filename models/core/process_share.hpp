// Work shared by processes that run the same computation in lockstep (MPI ranks under mpirun,
// docs/distributed.md): every process computes its own groups of a result array, then every
// process gets the whole array. The models know nothing of MPI; studies/distribute.hpp gives the
// MPI implementation, and without one (nullptr) a process computes everything itself.
//
// Groups are dealt out cyclically, group g to part g % parts: neighbouring groups (layers of a
// grid, consecutive poses) often cost alike, so every part gets a fair share of the costly ones.
// The result does not depend on the number of parts: each group is computed by the same code
// wherever it is computed.
//
// Example (a loop over n items of a trivially copyable type):
//   for (std::size_t i = 0; i < n; ++i)
//     if (owns(share, i)) out[i] = compute(i);
//   share_groups(share, out.data(), n, sizeof out[0]);
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace pkmopt {

class ProcessShare {
 public:
  virtual ~ProcessShare() = default;
  virtual int parts() const = 0;  ///< processes sharing the work (>= 1)
  virtual int part() const = 0;   ///< this process, 0..parts()-1
  /// Every process passes its bytes; every process gets every part's bytes, part 0 first.
  virtual std::vector<std::vector<char>> all_gather(std::span<const char> mine) const = 0;
};

/// Whether this process computes group g (always, without a share).
inline bool owns(const ProcessShare* share, std::size_t g) {
  return share == nullptr || share->parts() <= 1 ||
         g % static_cast<std::size_t>(share->parts()) == static_cast<std::size_t>(share->part());
}

/// After every process computed its own groups of `data` (`groups` groups of `group_bytes`
/// bytes, group g at data + g * group_bytes), gives every process all of them. No-op without a
/// share or with one part.
void share_groups(const ProcessShare* share, void* data, std::size_t groups,
                  std::size_t group_bytes);

}  // namespace pkmopt
