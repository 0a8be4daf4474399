// remeshDeck: the stages composed over the parts of a deck (pipeline.h).
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include <unordered_set>

#include "io/atomic_file.h"
#include "io/text_scan.h"
#include "json/json.h"
#include "pipeline/half_pass.h"
#include "pipeline/remesh_part.h"
#include "pipeline/seam_spacing.h"
#include "voxremesh/deck_assembly.h"
#include "voxremesh/errors.h"
#include "voxremesh/pipeline.h"

namespace voxremesh {

namespace {

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Adds the stage times of an earlier pass over a part to `part`'s.
void addPartTimes(RemeshedPart& part, const RemeshedPart& earlier) {
  part.volumeSeconds += earlier.volumeSeconds;
  part.extractSeconds += earlier.extractSeconds;
  part.optimizeSeconds += earlier.optimizeSeconds;
  part.acceptSeconds += earlier.acceptSeconds;
  part.totalSeconds += earlier.totalSeconds;
}

/// Nodes of a part closer than this share of its target size are one node of its surface: a
/// slit between them is no boundary a remesh could keep.
constexpr double kCoincidentShare = 1e-3;

/// For each plan, a model holding the part's shells plus the shells of other parts that share a
/// node with it (so that buildSheets still finds the seams), and the nodes they use: sheets and
/// volumes then cost what the part costs, not what the deck costs. A part's own coincident nodes
/// are merged in its model (mergeCoincidentNodes, within kCoincidentShare of its target size);
/// `mergedNodes` receives per plan how many. The models are filled in parallel (in the caller's
/// task arena), each on its own.
std::vector<FeModel> partModels(const FeModel& deck, const std::vector<PartPlan>& plans,
                                std::vector<std::size_t>& mergedNodes) {
  std::unordered_map<Id, std::size_t> planOf;
  for (std::size_t i = 0; i < plans.size(); ++i) planOf[plans[i].part] = i;
  const std::unordered_map<Id, std::size_t> nodeIndex = deck.nodeIndex();
  // The planned parts using each node (most nodes: one).
  std::unordered_map<Id, std::vector<std::size_t>> plansOfNode;
  for (const Shell& shell : deck.shells) {
    const auto it = planOf.find(shell.part);
    if (it == planOf.end()) continue;
    for (int c = 0; c < shell.nodeCount; ++c) {
      std::vector<std::size_t>& list = plansOfNode[shell.nodes[static_cast<std::size_t>(c)]];
      if (std::find(list.begin(), list.end(), it->second) == list.end()) list.push_back(it->second);
    }
  }
  std::vector<FeModel> models(plans.size());
  std::vector<std::size_t> targets;
  for (const Shell& shell : deck.shells) {
    targets.clear();
    for (int c = 0; c < shell.nodeCount; ++c) {
      const auto it = plansOfNode.find(shell.nodes[static_cast<std::size_t>(c)]);
      if (it == plansOfNode.end()) continue;
      for (const std::size_t plan : it->second)
        if (std::find(targets.begin(), targets.end(), plan) == targets.end())
          targets.push_back(plan);
    }
    for (const std::size_t plan : targets) models[plan].shells.push_back(shell);
  }
  mergedNodes.assign(plans.size(), 0);
  tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
    FeModel& model = models[i];
    std::unordered_set<Id> used;
    for (const Shell& shell : model.shells)
      for (int c = 0; c < shell.nodeCount; ++c)
        if (used.insert(shell.nodes[static_cast<std::size_t>(c)]).second)
          model.nodes.push_back(deck.nodes[nodeIndex.at(shell.nodes[static_cast<std::size_t>(c)])]);
    mergedNodes[i] = pipeline::mergeCoincidentNodes(model, plans[i].part,
                                                    kCoincidentShare * plans[i].targetSize);
  });
  return models;
}

/// Per plan, the smallest target size among it and the planned parts whose shells its model holds
/// (the parts it shares nodes with), so that both sides of a seam place the same nodes on it.
std::vector<double> junctionSpacings(const std::vector<FeModel>& models,
                                     const std::vector<PartPlan>& plans) {
  std::unordered_map<Id, double> sizeOf;
  for (const PartPlan& plan : plans) sizeOf[plan.part] = plan.targetSize;
  std::vector<double> spacing(plans.size());
  for (std::size_t i = 0; i < plans.size(); ++i) {
    spacing[i] = plans[i].targetSize;
    for (const Id other : shellPartIds(models[i]))
      if (const auto it = sizeOf.find(other); it != sizeOf.end())
        spacing[i] = std::min(spacing[i], it->second);
  }
  return spacing;
}

/// The index of each plan by its part.
std::unordered_map<Id, std::size_t> planIndex(const std::vector<PartPlan>& plans) {
  std::unordered_map<Id, std::size_t> planOf;
  for (std::size_t i = 0; i < plans.size(); ++i) planOf[plans[i].part] = i;
  return planOf;
}

/// The nodes the shells of the planned parts use.
std::unordered_set<Id> plannedNodes(const FeModel& deck,
                                    const std::unordered_map<Id, std::size_t>& planOf) {
  std::unordered_set<Id> nodes;
  for (const Shell& shell : deck.shells)
    if (planOf.count(shell.part))
      for (int c = 0; c < shell.nodeCount; ++c) nodes.insert(shell.nodes[std::size_t(c)]);
  return nodes;
}

/// Per plan, the indices (into deck.shells) of the part's shells that lie on faces of solid
/// elements (all corners are nodes of solid elements).
std::vector<std::vector<std::size_t>> shellsOnSolids(const FeModel& deck,
                                                     const std::vector<PartPlan>& plans) {
  const std::unordered_map<Id, std::size_t> planOf = planIndex(plans);
  const std::unordered_set<Id> solid = solidElementNodes(deck, plannedNodes(deck, planOf));
  std::vector<std::vector<std::size_t>> onSolids(plans.size());
  if (solid.empty()) return onSolids;
  for (std::size_t s = 0; s < deck.shells.size(); ++s) {
    const Shell& shell = deck.shells[s];
    const auto it = planOf.find(shell.part);
    if (it == planOf.end()) continue;
    bool onSolid = true;
    for (int c = 0; c < shell.nodeCount && onSolid; ++c)
      onSolid = solid.count(shell.nodes[std::size_t(c)]) > 0;
    if (onSolid) onSolids[it->second].push_back(s);
  }
  return onSolids;
}

/// Per plan, the indices (into deck.shells) of the part's shells that use the same nodes as another
/// shell of the part (a duplicate element, every copy), ascending; `named` receives per plan the
/// first such pairs in words ("shells 3 and 9"), empty when there is none.
std::vector<std::vector<std::size_t>> duplicateShells(const FeModel& deck,
                                                      const std::vector<PartPlan>& plans,
                                                      std::vector<std::string>& named) {
  const std::unordered_map<Id, std::size_t> planOf = planIndex(plans);
  // (plan, sorted node IDs) -> the shells using exactly those nodes
  std::map<std::pair<std::size_t, std::array<Id, 4>>, std::vector<std::size_t>> copies;
  for (std::size_t s = 0; s < deck.shells.size(); ++s) {
    const Shell& shell = deck.shells[s];
    const auto it = planOf.find(shell.part);
    if (it == planOf.end()) continue;
    std::array<Id, 4> key{0, 0, 0, 0};
    std::copy(shell.nodes.begin(), shell.nodes.begin() + shell.nodeCount, key.begin());
    std::sort(key.begin(), key.end());
    copies[{it->second, key}].push_back(s);
  }
  constexpr std::size_t kNamedPairs = 3;
  std::vector<std::vector<std::size_t>> result(plans.size());
  std::vector<std::size_t> pairs(plans.size(), 0);
  named.assign(plans.size(), std::string());
  for (const auto& [key, shells] : copies) {
    if (shells.size() < 2) continue;
    const std::size_t plan = key.first;
    result[plan].insert(result[plan].end(), shells.begin(), shells.end());
    if (pairs[plan]++ < kNamedPairs)
      named[plan] += (named[plan].empty() ? "shells " : ", shells ") +
                     std::to_string(deck.shells[shells[0]].id) + " and " +
                     std::to_string(deck.shells[shells[1]].id);
  }
  for (std::size_t i = 0; i < plans.size(); ++i) {
    std::sort(result[i].begin(), result[i].end());
    if (pairs[i] > kNamedPairs)
      named[i] += " and " + std::to_string(pairs[i] - kNamedPairs) + " more";
  }
  return result;
}

/// Shells of remeshed parts that stay as they are: while the deck is remeshed they carry a part
/// ID of their own (above every part ID of the deck), so that they count as a kept neighbour whose
/// seam nodes the rest of their part keeps; `restore` (or the destructor, when the remesh throws)
/// gives them their part back.
class HeldShells {
 public:
  explicit HeldShells(FeModel& deck) : deck_(deck) {}
  HeldShells(const HeldShells&) = delete;
  HeldShells& operator=(const HeldShells&) = delete;
  ~HeldShells() { restore(); }

  /// Gives the shells of `plan` listed in `shells` (indices into deck.shells) a held part ID.
  void hold(const PartPlan& plan, const std::vector<std::size_t>& shells) {
    if (next_ == 0) {  // the first held ID: above every part ID of the deck
      next_ = 1;
      for (const Shell& shell : deck_.shells) next_ = std::max(next_, shell.part + 1);
      for (const Part& part : deck_.parts) next_ = std::max(next_, part.id + 1);
    }
    const Id held = next_++;
    partOfHeld_[held] = plan.part;
    for (const std::size_t s : shells) deck_.shells[s].part = held;
  }

  /// Gives every held shell its own part again (once).
  void restore() {
    if (partOfHeld_.empty()) return;
    for (Shell& shell : deck_.shells) {
      const auto it = partOfHeld_.find(shell.part);
      if (it != partOfHeld_.end()) shell.part = it->second;
    }
    partOfHeld_.clear();
  }

 private:
  FeModel& deck_;
  std::unordered_map<Id, Id> partOfHeld_;  ///< held part ID -> the part the shells belong to
  Id next_ = 0;                            ///< the next held part ID (0: not counted yet)
};

/// Per plan, the nodes of its part's shells that other keywords use as points (hardPointNodes).
std::vector<std::unordered_set<Id>> partHardPoints(const FeModel& deck,
                                                   const std::vector<PartPlan>& plans) {
  const std::unordered_map<Id, std::size_t> planOf = planIndex(plans);
  const std::unordered_set<Id> hard = hardPointNodes(deck, plannedNodes(deck, planOf));
  std::vector<std::unordered_set<Id>> result(plans.size());
  if (hard.empty()) return result;
  for (const Shell& shell : deck.shells) {
    const auto it = planOf.find(shell.part);
    if (it == planOf.end()) continue;
    for (int c = 0; c < shell.nodeCount; ++c)
      if (hard.count(shell.nodes[std::size_t(c)]))
        result[it->second].insert(shell.nodes[std::size_t(c)]);
  }
  return result;
}

/// The parts other than `part` with shells in `model` (ascending).
std::vector<Id> otherParts(const FeModel& model, Id part) {
  std::vector<Id> parts = shellPartIds(model);
  parts.erase(std::remove(parts.begin(), parts.end(), part), parts.end());
  return parts;
}

/// Whether plan i, kept in the first round, is tried again at half its size: its attempts failed
/// the acceptance (it was not refused), retries are allowed, and a part it shares nodes with is
/// remeshed too, so that the seams between them can get the closer nodes its own retries cannot
/// give them.
bool mayHalve(std::size_t i, const RemeshedPart& part, const std::vector<FeModel>& models,
              const std::vector<PartPlan>& plans, const std::vector<std::uint8_t>& keptFromStart,
              const RemeshSettings& settings) {
  if (part.status != PartStatus::Kept || part.attempts == 0 || settings.retries < 1) return false;
  const std::vector<Id> others = otherParts(models[i], plans[i].part);
  for (std::size_t j = 0; j < plans.size(); ++j)
    if (j != i && !keptFromStart[j] &&
        std::binary_search(others.begin(), others.end(), plans[j].part))
      return true;
  return false;
}

/// A part tried again at a fraction of its size (mayHalve; `size` says which, in words, e.g.
/// "half the size") says so: "retried" when it passed, with what the larger sizes gave
/// (`earlierReason`, the full size's in words when it is the first halving); every size's
/// attempts when it was kept again.
void describeHalved(RemeshedPart& part, const std::string& earlierReason, const std::string& size) {
  const std::string earlier = earlierReason.rfind("at the full size: ", 0) == 0
                                  ? earlierReason
                                  : "at the full size: " + earlierReason;
  const std::string at = "at " + size + ", its seams refined with it";
  if (part.status == PartStatus::Kept) {
    part.reason = earlier + "; " + at + ": " + part.reason;
    return;
  }
  part.status = PartStatus::Retried;
  part.reason = at + " (" + earlier + ")" + (part.reason.empty() ? "" : "; " + part.reason);
}

/// Per plan, the plans whose parts share nodes with it (their shells are in its model), ascending.
std::vector<std::vector<std::size_t>> planNeighbours(const std::vector<FeModel>& models,
                                                     const std::vector<PartPlan>& plans) {
  const std::unordered_map<Id, std::size_t> planOf = planIndex(plans);
  std::vector<std::vector<std::size_t>> result(plans.size());
  for (std::size_t i = 0; i < plans.size(); ++i) {
    for (const Id other : otherParts(models[i], plans[i].part))
      if (const auto it = planOf.find(other); it != planOf.end()) result[i].push_back(it->second);
    std::sort(result[i].begin(), result[i].end());
  }
  return result;
}

/// The parts of `fixed` (ascending IDs) whose shells are in `part`'s model: its kept neighbours.
std::vector<Id> keptNeighbours(const FeModel& model, Id part, const std::vector<Id>& fixed) {
  std::vector<Id> result;
  for (const Id other : otherParts(model, part))
    if (std::binary_search(fixed.begin(), fixed.end(), other)) result.push_back(other);
  return result;
}

/// The reason of a part kept when it was done again in a later round: what its earlier round
/// gave, so that a part lost to a kept neighbour says so. `before`: the earlier round's result;
/// `after`: this round's (kept); `itself`: the part was kept in the earlier round and tried again
/// with all its seams fixed.
std::string redoneReason(const RemeshedPart& before, const RemeshedPart& after, bool itself,
                         const std::vector<Id>& neighbours) {
  const std::string again = "; again with every seam keeping its neighbours' nodes: ";
  if (itself) {
    const std::size_t last = before.reason.rfind(again);
    if (last != std::string::npos && before.reason.substr(last + again.size()) == after.reason)
      return before.reason;  // tried with all its seams fixed in an earlier round already
    return before.reason + again + after.reason;
  }
  if (before.status == PartStatus::Kept) return after.reason;
  std::string parts;
  for (const Id part : neighbours) parts += (parts.empty() ? "" : ", ") + std::to_string(part);
  return "its first mesh passed, but not with its seams along kept part" +
         std::string(neighbours.size() == 1 ? " " : "s ") + parts +
         " keeping their nodes: " + after.reason;
}

/// The parts with shells that `plans` leaves out (ascending IDs): they keep their elements.
std::vector<Id> unplannedParts(const FeModel& deck, const std::vector<PartPlan>& plans) {
  std::vector<Id> planned;
  for (const PartPlan& plan : plans) planned.push_back(plan.part);
  std::sort(planned.begin(), planned.end());
  std::vector<Id> result;
  for (const Id part : shellPartIds(deck))
    if (!std::binary_search(planned.begin(), planned.end(), part)) result.push_back(part);
  return result;
}

/// The plans (ascending indices) to do again after a round: those other than `skip` (kept from the
/// start) whose part model holds a shell of another part of `newlyKept` (a neighbour sharing
/// nodes), since their seams along it must now keep its nodes; and the parts of `newlyKept` that
/// have neighbours, tried again with all their seams fixed.
std::vector<std::size_t> neighboursToRedo(const std::vector<FeModel>& models,
                                          const std::vector<PartPlan>& plans,
                                          const std::vector<std::uint8_t>& skip,
                                          std::vector<Id> newlyKept) {
  std::sort(newlyKept.begin(), newlyKept.end());
  std::vector<std::size_t> redo;
  if (newlyKept.empty()) return redo;
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (skip[i]) continue;
    const Id part = plans[i].part;
    const bool kept = std::binary_search(newlyKept.begin(), newlyKept.end(), part);
    const bool touches =
        std::any_of(models[i].shells.begin(), models[i].shells.end(), [&](const Shell& shell) {
          return shell.part != part &&
                 (kept || std::binary_search(newlyKept.begin(), newlyKept.end(), shell.part));
        });
    if (touches) redo.push_back(i);
  }
  return redo;
}

}  // namespace

const char* partStatusName(PartStatus status) {
  switch (status) {
    case PartStatus::Remeshed:
      return "remeshed";
    case PartStatus::Retried:
      return "retried";
    case PartStatus::Kept:
      return "kept";
  }
  return "kept";
}

std::size_t RemeshReport::count(PartStatus status) const {
  return static_cast<std::size_t>(std::count_if(
      parts.begin(), parts.end(), [&](const RemeshedPart& part) { return part.status == status; }));
}

RemeshReport remeshDeck(FeModel& deck, const RemeshSettings& asked,
                        const RemeshProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  // The part models hold only the shells around each part: its sheets are split at the folds
  // found on the whole deck.
  RemeshSettings settings = asked;
  if (!settings.sheets.sheetCuts)
    settings.sheets.sheetCuts =
        std::make_shared<const std::vector<std::array<Id, 2>>>(findSheetCuts(deck));
  RemeshReport report;
  std::vector<PartPlan> plans = planRemesh(deck, settings);
  report.parts.resize(plans.size());
  std::vector<QuadMesh> meshes(plans.size());
  std::mutex progressMutex;
  std::size_t done = 0;
  const auto tell = [&](const std::string& stage, Id part, bool finished) {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(progressMutex);
    if (finished) ++done;
    progress(stage, part, plans.empty() ? 1.0 : static_cast<double>(done) / plans.size());
  };
  const int threads =
      settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  // Shells on faces of solid elements stay: a part made of them only is kept, the shells of a
  // part with others are held (a kept neighbour of the rest of their part).
  report.seamsBefore = deckSeams(deck);
  // Duplicate elements (two shells of a part on the same nodes: a mirrored model's shells on its
  // plane of symmetry, say) stay too: remeshing would merge them into one and lose the stiffness
  // and the IDs the user gave them.
  const std::vector<std::vector<std::size_t>> onSolids = shellsOnSolids(deck, plans);
  std::vector<std::string> duplicatePairs;
  const std::vector<std::vector<std::size_t>> duplicates =
      duplicateShells(deck, plans, duplicatePairs);
  HeldShells held(deck);
  std::vector<std::uint8_t> keptFromStart(plans.size(), 0);
  for (std::size_t i = 0; i < plans.size(); ++i) {
    std::vector<std::size_t> staying = onSolids[i];
    staying.insert(staying.end(), duplicates[i].begin(), duplicates[i].end());
    std::sort(staying.begin(), staying.end());
    staying.erase(std::unique(staying.begin(), staying.end()), staying.end());
    if (staying.empty()) continue;
    if (staying.size() < plans[i].shells) {
      held.hold(plans[i], staying);
      continue;
    }
    keptFromStart[i] = 1;
    RemeshedPart& part = report.parts[i];
    part.plan = plans[i];
    const std::string shells = "its " + std::to_string(plans[i].shells) + " shells";
    if (duplicates[i].empty())
      part.reason = shells + " lie on faces of solid elements (remeshing would detach them)";
    else if (onSolids[i].empty())
      part.reason =
          shells + " are duplicate elements (" + duplicatePairs[i] + " use the same nodes)";
    else
      part.reason = shells + " lie on faces of solid elements or are duplicate elements (" +
                    duplicatePairs[i] + " use the same nodes)";
    tell("extract", plans[i].part, true);
  }
  std::vector<std::size_t> mergedNodes;
  std::vector<FeModel> partModelsBuilt;
  arena.execute([&] { partModelsBuilt = partModels(deck, plans, mergedNodes); });
  const std::vector<FeModel> models = std::move(partModelsBuilt);
  const std::vector<std::vector<std::size_t>> neighbours = planNeighbours(models, plans);
  std::vector<double> ownSize;  // each plan's target size before the halving passes
  for (const PartPlan& plan : plans) ownSize.push_back(plan.targetSize);
  std::vector<double> junctionSpacing;
  const std::vector<std::unordered_set<Id>> hardPoints = partHardPoints(deck, plans);
  std::unordered_map<Id, double> seamSpacing;
  pipeline::SeamSampling seamSampling;
  // Parts whose seams keep their nodes: from the start those not planned (held shells too) and
  // those on solids, then every part kept in a round.
  std::vector<Id> fixed = unplannedParts(deck, plans);
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (keptFromStart[i])
      fixed.push_back(plans[i].part);
    else
      todo.push_back(i);
  }
  std::sort(fixed.begin(), fixed.end());
  // The seams' spacing and sampling, for the first round and the halving passes. Later rounds
  // keep them: a part redone there meets parts that are not, whose seams must stay as they are.
  const auto updateSpacing = [&] {
    junctionSpacing = junctionSpacings(models, plans);
    arena.execute([&] {
      seamSpacing =
          pipeline::seamNodeSpacing(models, plans, junctionSpacing, keptFromStart, settings);
      seamSampling = pipeline::seamSampling(models, plans, junctionSpacing, keptFromStart,
                                            seamSpacing, hardPoints, fixed, settings);
    });
  };
  updateSpacing();
  // Rounds: the parts to do are remeshed with the seams along fixed parts keeping their nodes (a
  // fixed part itself with all its seams fixed); the neighbours of a part kept in a round, and
  // that part, are done again in the next. After the first round, when parts were kept that
  // mayHalve allows, the first round is done again with those at half their size; its results
  // stay group by group (takeHalvedGroups) where more parts pass so, none that passed is lost
  // and no more seam points hang. Those still kept are tried so at a quarter of their size, and
  // so on: settings.retries halvings at most, as a part's own retries.
  RemeshSettings halvedSettings = settings;  // a halved part's retries stop at the same voxel
  std::string halvedSize;                    // the size of the halved parts, in words
  std::vector<std::string> fullSizeReason(plans.size());  // non-empty: the plan is halved
  // Remeshes the listed plans in parallel; `first`: in the first round.
  const auto remeshAll = [&](const std::vector<std::size_t>& list, bool first, bool tellDone) {
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), list.size(), [&](std::size_t t) {
        const std::size_t i = list[t];
        const bool isFixed = std::binary_search(fixed.begin(), fixed.end(), plans[i].part);
        const pipeline::PartSurroundings surroundings{
            junctionSpacing[i], isFixed ? otherParts(models[i], plans[i].part) : fixed,
            hardPoints[i], &seamSpacing, &seamSampling};
        const bool halved = !fullSizeReason[i].empty();
        // Isolated: a thread waiting inside this part's parallel loops runs none of another
        // part's work, so that the part's stage times are its own.
        RemeshedPart result;
        const auto partStart = std::chrono::steady_clock::now();
        tbb::this_task_arena::isolate([&] {
          result = pipeline::remeshPart(
              models[i], plans[i], halved ? halvedSettings : settings, surroundings, meshes[i],
              [&](const char* stage) { tell(stage, plans[i].part, false); });
        });
        result.totalSeconds = since(partStart);
        if (!first) addPartTimes(result, report.parts[i]);
        if (halved && first)
          describeHalved(result, fullSizeReason[i], halvedSize);
        else if (!first && result.status == PartStatus::Kept)
          result.reason = redoneReason(report.parts[i], result, isFixed,
                                       keptNeighbours(models[i], plans[i].part, fixed));
        report.parts[i] = std::move(result);
        if (tellDone) tell("extract", plans[i].part, true);
      });
    });
  };
  for (bool first = true; !todo.empty(); first = false) {
    remeshAll(todo, first, first);
    for (int level = 1; first && level <= settings.retries; ++level) {
      bool anyHalvable = false;
      for (const std::size_t i : todo)
        if (mayHalve(i, report.parts[i], models, plans, keptFromStart, settings)) {
          fullSizeReason[i] = report.parts[i].reason;
          anyHalvable = true;
        }
      if (!anyHalvable) break;
      const int share = 1 << level;  // the halved parts' size: 1 / share of their own
      halvedSettings.retries = std::max(0, settings.retries - level);
      halvedSettings.finestVoxelShare = std::min(1.0, share * settings.finestVoxelShare);
      halvedSize = level == 1 ? "half the size" : "1/" + std::to_string(share) + " of the size";
      pipeline::RoundResult full{report.parts, meshes, plans};
      std::vector<std::uint8_t> halved(plans.size(), 0), redone(plans.size(), 0);
      for (const std::size_t i : todo) redone[i] = 1;
      for (std::size_t i = 0; i < plans.size(); ++i)
        if (!fullSizeReason[i].empty()) {
          plans[i].targetSize = ownSize[i] / share;
          halved[i] = 1;
        }
      updateSpacing();
      // Only the groups' parts get other seams or sizes: the rest would mesh as before.
      const std::vector<std::size_t> groups = pipeline::halvingGroups(neighbours, halved, redone);
      std::vector<std::size_t> members;
      for (const std::size_t i : todo)
        if (groups[i] != pipeline::kNoGroup) members.push_back(i);
      remeshAll(members, true, false);
      pipeline::RoundResult half{std::move(report.parts), std::move(meshes), std::move(plans)};
      pipeline::takeHalvedGroups(full, half, groups, neighbours);
      report.parts = std::move(full.parts);
      meshes = std::move(full.meshes);
      plans = std::move(full.plans);
      updateSpacing();
      fullSizeReason.assign(plans.size(), std::string());
    }
    std::vector<Id> newlyKept;
    for (const std::size_t i : todo)
      if (report.parts[i].status == PartStatus::Kept &&
          !std::binary_search(fixed.begin(), fixed.end(), plans[i].part))
        newlyKept.push_back(plans[i].part);
    todo = neighboursToRedo(models, plans, keptFromStart, newlyKept);
    fixed.insert(fixed.end(), newlyKept.begin(), newlyKept.end());
    std::sort(fixed.begin(), fixed.end());
  }
  // A kept part reports the quality of what it writes back: its original shells. Judging them
  // never stops the deck (out of memory, say): the part then reports its last attempt.
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
      RemeshedPart& part = report.parts[i];
      if (part.status != PartStatus::Kept) return;
      try {
        part.acceptance = pipeline::keptPartQuality(models[i], plans[i], settings);
        part.quads = part.acceptance.quads;
        part.trias = part.acceptance.trias;
      } catch (const std::exception&) {
      }
    });
  });
  std::vector<QuadMesh> accepted;
  for (std::size_t i = 0; i < plans.size(); ++i)
    if (report.parts[i].status != PartStatus::Kept) accepted.push_back(std::move(meshes[i]));
  if (progress) progress("assemble", 0, 1.0);
  const auto assemblyStart = std::chrono::steady_clock::now();
  std::unordered_set<Id> allHardPoints;
  for (const std::unordered_set<Id>& part : hardPoints)
    allHardPoints.insert(part.begin(), part.end());
  report.assembly = replacePartMeshes(deck, accepted, allHardPoints);
  held.restore();
  for (std::size_t i = 0; i < plans.size(); ++i) {
    std::string& reason = report.parts[i].reason;
    if (mergedNodes[i] > 0 && report.parts[i].status != PartStatus::Kept)
      reason = (reason.empty() ? "" : reason + "; ") + std::to_string(mergedNodes[i]) +
               " coincident nodes of the part merged (remeshed as one surface)";
  }
  for (std::size_t i = 0; i < plans.size(); ++i) {
    if (keptFromStart[i]) continue;
    std::string& reason = report.parts[i].reason;
    if (!duplicates[i].empty())
      reason = std::to_string(duplicates[i].size()) + " of its " + std::to_string(plans[i].shells) +
               " shells are duplicate elements (" + duplicatePairs[i] +
               " use the same nodes) and are kept" + (reason.empty() ? "" : "; " + reason);
    if (!onSolids[i].empty())
      reason = std::to_string(onSolids[i].size()) + " of its " + std::to_string(plans[i].shells) +
               " shells lie on faces of solid elements and are kept" +
               (reason.empty() ? "" : "; " + reason);
  }
  report.seamsAfter = deckSeams(deck);
  report.assemblySeconds = since(assemblyStart);
  report.totalSeconds = since(start);
  return report;
}

std::string remeshReportJson(const RemeshReport& report) {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer,
                "{\n  \"remeshed\": %zu,\n  \"retried\": %zu,\n  \"kept\": %zu,\n  \"parts\": [",
                report.count(PartStatus::Remeshed), report.count(PartStatus::Retried),
                report.count(PartStatus::Kept));
  std::string out = buffer;
  for (std::size_t i = 0; i < report.parts.size(); ++i) {
    const RemeshedPart& part = report.parts[i];
    const PartAcceptance& a = part.acceptance;
    std::snprintf(buffer, sizeof buffer,
                  "%s\n    {\"part\": %lld, \"status\": \"%s\", \"elements_before\": %zu, "
                  "\"quads\": %zu, \"trias\": %zu, \"attempts\": %d, \"failing\": %zu, "
                  "\"folded\": %zu, \"degenerate_corners\": %zu, \"components\": [%zu, %zu], "
                  "\"loops\": [%zu, %zu]",
                  i ? "," : "", static_cast<long long>(part.plan.part), partStatusName(part.status),
                  part.plan.shells, part.quads, part.trias, part.attempts, a.failing, a.folded,
                  a.degenerateCorners, a.componentsBefore, a.componentsAfter, a.loopsBefore,
                  a.loopsAfter);
    out += buffer;
    const std::pair<const char*, double> numbers[] = {
        {"target_size", part.plan.targetSize},
        {"voxel_size", part.voxelSize},
        {"failing_share", a.failingShare},
        {"quality_index", a.qualityIndex},
        {"distance", a.distance},
        {"distance_limit", a.distanceLimit},
        {"area_before", a.areaBefore},
        {"area_after", a.areaAfter},
        {"junction_length", a.junctionLength},
        {"junction_length_lost", a.junctionLengthLost},
        {"volume_seconds", part.volumeSeconds},
        {"extract_seconds", part.extractSeconds},
        {"optimize_seconds", part.optimizeSeconds},
        {"accept_seconds", part.acceptSeconds},
        {"seconds", part.totalSeconds}};
    for (const auto& [key, value] : numbers) {
      out += std::string(", \"") + key + "\": ";
      if (std::isfinite(value))
        io::appendShortest(out, value);
      else
        out += "null";
    }
    out += ", \"reason\": ";
    out += json::quote(part.reason) + "}";
  }
  out += "\n  ],\n  \"remaps\": [";
  const AssemblyReport& assembly = report.assembly;
  for (std::size_t i = 0; i < assembly.remaps.size(); ++i) {
    const NodeRemap& remap = assembly.remaps[i];
    std::snprintf(buffer, sizeof buffer,
                  "%s\n    {\"keyword\": %s, \"line\": %zu, \"old_node\": %lld, "
                  "\"new_node\": %lld, \"part\": %lld, \"distance\": %.17g}",
                  i ? "," : "", json::quote(remap.keyword).c_str(), remap.line,
                  static_cast<long long>(remap.oldNode), static_cast<long long>(remap.newNode),
                  static_cast<long long>(remap.part), remap.distance);
    out += buffer;
  }
  out += "\n  ],\n  \"unmapped\": [";
  for (std::size_t i = 0; i < assembly.unmapped.size(); ++i) {
    const UnmappedReference& ref = assembly.unmapped[i];
    std::snprintf(buffer, sizeof buffer,
                  "%s\n    {\"keyword\": %s, \"line\": %zu, \"node\": %lld, ", i ? "," : "",
                  json::quote(ref.keyword).c_str(), ref.line, static_cast<long long>(ref.node));
    out += buffer;
    out += "\"reason\": " + json::quote(ref.reason) + "}";
  }
  // Seams: every pair of parts that shared nodes before or after, with both counts.
  out += "\n  ],\n  \"seams\": [";
  std::map<std::pair<Id, Id>, std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& [key, count] : report.seamsBefore.sharedNodes) pairs[key].first = count;
  for (const auto& [key, count] : report.seamsAfter.sharedNodes) pairs[key].second = count;
  bool firstPair = true;
  for (const auto& [key, counts] : pairs) {
    std::snprintf(buffer, sizeof buffer,
                  "%s\n    {\"parts\": [%lld, %lld], \"shared_nodes_in\": %zu, "
                  "\"shared_nodes_out\": %zu}",
                  firstPair ? "" : ",", static_cast<long long>(key.first),
                  static_cast<long long>(key.second), counts.first, counts.second);
    out += buffer;
    firstPair = false;
  }
  std::snprintf(buffer, sizeof buffer,
                "\n  ],\n  \"t_junction_edges_in\": %zu,\n  \"t_junction_edges_out\": %zu,\n"
                "  \"hanging_nodes_in\": %zu,\n  \"hanging_nodes_out\": %zu,\n"
                "  \"removed_nodes\": %zu,\n  \"new_nodes\": %zu,\n  \"hard_points_kept\": %zu,\n"
                "  \"element_loads_rewritten\": %zu,\n  \"element_set_members_rewritten\": %zu,\n"
                "  \"seconds\": %.6f\n}\n",
                report.seamsBefore.tJunctionEdges, report.seamsAfter.tJunctionEdges,
                report.seamsBefore.hangingNodes, report.seamsAfter.hangingNodes,
                assembly.removedNodes, assembly.newNodes, assembly.hardPointsKept,
                assembly.elementLoadsRewritten, assembly.elementSetMembersRewritten,
                report.totalSeconds);
  return out + buffer;
}

void writeRemeshReport(const RemeshReport& report, const std::filesystem::path& path) {
  io::writeFileAtomically(path, remeshReportJson(report));
}

}  // namespace voxremesh
