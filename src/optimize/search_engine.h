// The search engine's loop, which every search of the optimisation runs: rounds over a worklist
// of items, each trying a local change at one place of the mesh (a point moved, a neighbourhood
// reconnected, a point pulled towards the original); the items of a round in classes that do not
// see each other's changes (runInClasses); an item tried in vain not tried again while nothing
// it depends on has changed since.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <type_traits>
#include <utility>
#include <vector>

#include "optimize/independent_classes.h"

namespace voxremesh::opt {

/// The tries that found nothing, by key (a point, a face), and per point the stamp at which it
/// last changed. Stamps are counts the caller raises between tries that may see each other's
/// changes; 0 is never. A try depends only on the positions (and faces) of some points: one that
/// found nothing finds nothing again until one of them changes.
template <class Key>
class VainTries {
 public:
  /// @param points  the number of points; every point named later is below it
  explicit VainTries(std::size_t points) : changedAt_(points, 0) {}

  /// The stamp of the last try of `key` in vain, or 0.
  std::uint32_t vainAt(const Key& key) const {
    if constexpr (std::is_integral_v<Key>) {
      return std::size_t(key) < vainAt_.size() ? vainAt_[std::size_t(key)] : 0;
    } else {
      const auto at = vainAt_.find(key);
      return at == vainAt_.end() ? 0 : at->second;
    }
  }

  /// Whether point v has changed at `stamp` or after.
  bool changedSince(CornerIndex v, std::uint32_t stamp) const { return changedAt_[v] >= stamp; }

  /// Whether `key` was tried in vain and none of `points` (a range of point indexes) has changed
  /// since.
  template <class Points>
  bool unchangedSinceVain(const Key& key, const Points& points) const {
    const std::uint32_t at = vainAt(key);
    return at != 0 && std::none_of(points.begin(), points.end(),
                                   [&](CornerIndex v) { return changedSince(v, at); });
  }

  /// Notes a try of `key` in vain at `stamp` (> 0).
  void noteVain(const Key& key, std::uint32_t stamp) {
    if constexpr (std::is_integral_v<Key>) {
      if (std::size_t(key) >= vainAt_.size()) vainAt_.resize(std::size_t(key) + 1, 0);
      vainAt_[std::size_t(key)] = stamp;
    } else {
      vainAt_[key] = stamp;
    }
  }

  /// Notes a change of point v at `stamp` (> 0).
  void noteChanged(CornerIndex v, std::uint32_t stamp) { changedAt_[v] = stamp; }

 private:
  std::conditional_t<std::is_integral_v<Key>, std::vector<std::uint32_t>,
                     std::map<Key, std::uint32_t>>
      vainAt_;
  std::vector<std::uint32_t> changedAt_;
};

/// How a kind of item shares a round with the others.
struct RoundRules {
  /// An item with a point of `depends` that an earlier class of the round changed waits for the
  /// next round (what its round found of the mesh there is stale); else it sees the change.
  bool waitForChanged = true;
  /// Items tried in vain with nothing changed since are dropped before the classes are formed;
  /// else they are skipped as their class comes up, so that the classes, and with them the order
  /// of the tries, are those the round would have without the record.
  bool dropBeforeClasses = true;
};

/// Up to `rounds` rounds of the engine over the items of `kind`, until a round changes nothing.
/// Per round: kind.items(round), the worklist from the mesh as it is, each item with members
/// `key` (what VainTries records it by), `access` (PointAccess: the points its try reads and
/// may change; moved out once the classes are formed) and `depends` (the points whose change
/// makes a try in vain worth making again);
/// items tried in vain with none of `depends` changed since are not tried. The items in classes
/// (independentClasses); as a class comes up, kind.startClass(); kind.tryItem(item) of its
/// items in parallel (it must read only the item's points and what startClass and apply set);
/// then, alone and in item order, kind.apply(item, result), which changes the mesh and returns
/// the points it changed (none: the try was in vain). After the round, kind.endRound(number of
/// items that changed something). Deterministic for any thread count.
/// @param pointCount  the number of points, constant through the rounds
/// @return the number of items that changed something
/// Throws what the kind throws.
template <class Kind>
std::size_t runEngineRounds(int rounds, std::size_t pointCount, const RoundRules& rules,
                            Kind& kind) {
  using Item = typename decltype(kind.items(0))::value_type;
  using Key = std::decay_t<decltype(std::declval<Item>().key)>;
  VainTries<Key> vain(pointCount);
  std::uint32_t stamp = 0;
  std::size_t changed = 0;
  for (int round = 0; round < rounds; ++round) {
    std::vector<Item> items = kind.items(round);
    const auto skipped = [&](const Item& item) {
      return vain.unchangedSinceVain(item.key, item.depends);
    };
    if (rules.dropBeforeClasses)
      items.erase(std::remove_if(items.begin(), items.end(), skipped), items.end());
    // The classes need the items' accesses; nothing reads them after.
    std::vector<PointAccess> access;
    access.reserve(items.size());
    for (Item& item : items) access.push_back(std::move(item.access));
    std::vector<std::uint8_t> changedThisRound(rules.waitForChanged ? pointCount : 0, 0);
    std::size_t roundChanged = 0;
    runInClasses(
        access, pointCount,
        [&](std::uint32_t i) {
          const Item& item = items[i];
          if (rules.waitForChanged &&
              std::any_of(item.depends.begin(), item.depends.end(),
                          [&](CornerIndex v) { return changedThisRound[v] != 0; }))
            return false;
          return rules.dropBeforeClasses || !skipped(item);
        },
        [&] {
          ++stamp;
          kind.startClass();
        },
        [&](std::uint32_t i) { return kind.tryItem(items[i]); },
        [&](std::uint32_t i, auto result) {
          const std::vector<CornerIndex> points = kind.apply(items[i], std::move(result));
          if (points.empty()) {
            vain.noteVain(items[i].key, stamp);
            return;
          }
          for (const CornerIndex v : points) {
            vain.noteChanged(v, stamp);
            if (rules.waitForChanged) changedThisRound[v] = 1;
          }
          ++roundChanged;
        });
    kind.endRound(roundChanged);
    changed += roundChanged;
    if (roundChanged == 0) break;
  }
  return changed;
}

}  // namespace voxremesh::opt
