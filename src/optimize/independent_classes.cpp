// independentClasses (independent_classes.h).
#include "optimize/independent_classes.h"

#include <stdexcept>

namespace voxremesh::opt {

namespace {

/// Appends class k to a point's list unless it is already its last entry (the lists grow in
/// item order, so the entries of one item are consecutive).
void note(std::vector<std::uint32_t>& list, std::uint32_t k) {
  if (list.empty() || list.back() != k) list.push_back(k);
}

}  // namespace

std::vector<std::vector<std::uint32_t>> independentClasses(const std::vector<PointAccess>& items,
                                                           std::size_t pointCount) {
  // Per point, the classes with an item reading it and those with an item changing it; a point is
  // near few items, so the lists are short.
  std::vector<std::vector<std::uint32_t>> readers(pointCount), writers(pointCount);
  std::vector<std::vector<std::uint32_t>> classes;
  std::vector<std::uint8_t> taken;
  for (std::uint32_t item = 0; item < items.size(); ++item) {
    const PointAccess& access = items[item];
    taken.assign(classes.size() + 1, 0);
    for (const std::vector<CornerIndex>* list : {&access.reads, &access.writes})
      for (const CornerIndex v : *list)
        if (v >= pointCount) throw std::out_of_range("independentClasses: point out of range");
    for (const CornerIndex v : access.reads)
      for (const std::uint32_t k : writers[v]) taken[k] = 1;
    for (const CornerIndex v : access.writes) {
      for (const std::uint32_t k : readers[v]) taken[k] = 1;
      for (const std::uint32_t k : writers[v]) taken[k] = 1;
    }
    std::uint32_t k = 0;
    while (taken[k]) ++k;
    if (k == classes.size()) classes.emplace_back();
    classes[k].push_back(item);
    for (const CornerIndex v : access.reads) note(readers[v], k);
    for (const CornerIndex v : access.writes) note(writers[v], k);
  }
  return classes;
}

}  // namespace voxremesh::opt
