#include "models/core/process_share.hpp"

#include <cstring>
#include <stdexcept>

namespace pkmopt {

void share_groups(const ProcessShare* share, void* data, std::size_t groups,
                  std::size_t group_bytes) {
  if (share == nullptr || share->parts() <= 1 || groups == 0 || group_bytes == 0) return;
  const auto parts = static_cast<std::size_t>(share->parts());
  const auto part = static_cast<std::size_t>(share->part());
  char* bytes = static_cast<char*>(data);
  std::vector<char> mine;
  for (std::size_t g = part; g < groups; g += parts)
    mine.insert(mine.end(), bytes + g * group_bytes, bytes + (g + 1) * group_bytes);
  const std::vector<std::vector<char>> all = share->all_gather(mine);
  if (all.size() != parts) throw std::logic_error("share_groups: a part is missing");
  for (std::size_t p = 0; p < parts; ++p) {
    std::size_t at = 0;
    for (std::size_t g = p; g < groups; g += parts, at += group_bytes) {
      if (at + group_bytes > all[p].size())
        throw std::logic_error("share_groups: a part sent fewer groups than it owns");
      std::memcpy(bytes + g * group_bytes, all[p].data() + at, group_bytes);
    }
  }
}

}  // namespace pkmopt
