// Which results of remeshDeck's half pass stay (half_pass.h).
#include "pipeline/half_pass.h"

#include <algorithm>
#include <utility>

#include "pipeline/remesh_part.h"

namespace voxremesh::pipeline {

namespace {

/// A point of one part's new mesh closer than this share of the target size to the inside of an
/// edge of a neighbour's new mesh hangs on it: their meshes do not conform there.
constexpr double kHangingShare = 0.005;

/// Over the pairs of accepted parts that share nodes, one of them in `among` (per plan, 1 or 0),
/// the points of one hanging on the other's edges (hangingPoints, within kHangingShare of the
/// smaller target size).
std::size_t hangingSeamPoints(const std::vector<QuadMesh>& meshes,
                              const std::vector<RemeshedPart>& parts,
                              const std::vector<std::vector<std::size_t>>& neighbours,
                              const std::vector<PartPlan>& plans,
                              const std::vector<std::uint8_t>& among) {
  std::size_t hanging = 0;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (parts[i].status == PartStatus::Kept) continue;
    for (const std::size_t j : neighbours[i]) {
      if (parts[j].status == PartStatus::Kept || !(among[i] || among[j])) continue;
      const double size = std::min(plans[i].targetSize, plans[j].targetSize);
      hanging += hangingPoints(meshes[i], meshes[j], kHangingShare * size);
    }
  }
  return hanging;
}

}  // namespace

std::vector<std::size_t> halvingGroups(const std::vector<std::vector<std::size_t>>& neighbours,
                                       const std::vector<std::uint8_t>& halved,
                                       const std::vector<std::uint8_t>& redone) {
  const std::size_t count = neighbours.size();
  std::vector<std::size_t> root(count, kNoGroup);
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  const auto join = [&](std::size_t a, std::size_t b) {
    for (const std::size_t i : {a, b})
      if (root[i] == kNoGroup) root[i] = i;
    const std::size_t ra = find(a), rb = find(b);
    root[std::max(ra, rb)] = std::min(ra, rb);
  };
  std::vector<std::uint8_t> finer(count, 0);
  for (std::size_t i = 0; i < count; ++i) {
    if (!halved[i]) continue;
    finer[i] = 1;
    for (const std::size_t j : neighbours[i]) finer[j] = finer[j] || redone[j];
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!finer[i]) continue;
    join(i, i);
    for (const std::size_t j : neighbours[i])
      if (redone[j]) join(i, j);
  }
  for (std::size_t i = 0; i < count; ++i)
    if (root[i] != kNoGroup) root[i] = find(i);
  return root;
}

void takeHalvedGroups(RoundResult& result, RoundResult& half, const std::vector<std::size_t>& group,
                      const std::vector<std::vector<std::size_t>>& neighbours) {
  std::vector<std::size_t> roots(group);
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  const auto swapGroup = [&](const std::vector<std::size_t>& members) {
    for (const std::size_t i : members) {
      std::swap(result.parts[i], half.parts[i]);
      std::swap(result.meshes[i], half.meshes[i]);
      std::swap(result.plans[i], half.plans[i]);
    }
  };
  for (const std::size_t root : roots) {
    if (root == kNoGroup) continue;
    std::vector<std::size_t> members;
    std::vector<std::uint8_t> among(group.size(), 0);
    std::size_t gained = 0, lost = 0;
    for (std::size_t i = 0; i < group.size(); ++i) {
      if (group[i] != root) continue;
      members.push_back(i);
      among[i] = 1;
      const bool was = result.parts[i].status != PartStatus::Kept;
      const bool is = half.parts[i].status != PartStatus::Kept;
      gained += is && !was;
      lost += was && !is;
    }
    if (lost > 0 || gained == 0) continue;
    const std::size_t before =
        hangingSeamPoints(result.meshes, result.parts, neighbours, result.plans, among);
    swapGroup(members);
    if (hangingSeamPoints(result.meshes, result.parts, neighbours, result.plans, among) > before)
      swapGroup(members);
  }
}

}  // namespace voxremesh::pipeline
