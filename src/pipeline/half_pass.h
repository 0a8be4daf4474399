// The half pass of remeshDeck: the parts kept in the first round are tried again at half their
// size with their neighbours; which of the pass's results stay, group by group. Internal to
// src/pipeline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxremesh/pipeline.h"

namespace voxremesh::pipeline {

/// Marks a plan the half pass leaves as it was (halvingGroups).
constexpr std::size_t kNoGroup = SIZE_MAX;

/// The groups of plans the half pass changes together. A halved plan and the redone plans sharing
/// nodes with it get a finer junction spacing, and the seams of their own redone neighbours follow
/// it: each of them is joined with those neighbours.
/// @param neighbours  per plan, the plans whose parts share nodes with it (symmetric)
/// @param halved      per plan, 1 when the pass halves its size
/// @param redone      per plan, 1 when the pass remeshes it again
/// @return per plan, the smallest plan index of its group, or kNoGroup for a plan the pass does
///         not change. Preconditions: the three vectors have one entry per plan.
std::vector<std::size_t> halvingGroups(const std::vector<std::vector<std::size_t>>& neighbours,
                                       const std::vector<std::uint8_t>& halved,
                                       const std::vector<std::uint8_t>& redone);

/// The parts, meshes and plans of one round, in plan order.
struct RoundResult {
  std::vector<RemeshedPart> parts;
  std::vector<QuadMesh> meshes;
  std::vector<PartPlan> plans;
};

/// Takes the half pass's results into `result` (the full size's) group by group, in the order of
/// their smallest plan index: a group's results are taken when more of its parts pass, none of
/// them that passed at the full size is lost, and no more points of accepted parts hang on a
/// neighbour's edges (hangingPoints, within 0.005 of the smaller target size). `half` is left with
/// the results not taken. Deterministic. Preconditions: `result`, `half` and `group`
/// (halvingGroups) have one entry per plan; `neighbours` as for halvingGroups.
void takeHalvedGroups(RoundResult& result, RoundResult& half, const std::vector<std::size_t>& group,
                      const std::vector<std::vector<std::size_t>>& neighbours);

}  // namespace voxremesh::pipeline
