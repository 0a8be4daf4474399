// Node lists and per-node data that name a region of a remeshed part (a node set, the nodes with
// an initial velocity) cover the same region of the new mesh: which new nodes do, and the text
// edits that say so. Internal to src/assembly.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "assembly/nearest_point.h"
#include "assembly/node_references.h"
#include "voxremesh/fe_model.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::assembly {

/// A new node of a remeshed part and where it lies on the part's old shells.
struct NewNodeSite {
  Id node = 0;
  Id part = 0;                    ///< the part whose mesh made the node first
  std::array<double, 3> xyz{};    ///< the node
  std::array<double, 3> onOld{};  ///< its closest point on the part's old shells
  std::array<Id, 4> corners{};    ///< the node IDs of the old shell that point lies on
  std::array<std::array<double, 3>, 4> cornerXyz{};
  int cornerCount = 0;
};

/// The new nodes of the remeshed parts, located on their parts' old shells, with a search for
/// the nearest of them. Deterministic: a node made by two meshes is located once, on the first
/// mesh's part.
class NewNodeSites {
 public:
  /// @param model     the deck before its shells are replaced
  /// @param meshes    the new meshes, one per part
  /// @param pointIds  per mesh, the node ID of each point
  /// @param firstNew  the lowest new node ID: points with a lower ID are old nodes, not located
  NewNodeSites(const FeModel& model, const std::vector<QuadMesh>& meshes,
               const std::vector<std::vector<Id>>& pointIds, Id firstNew);
  NewNodeSites(const NewNodeSites&) = delete;
  NewNodeSites& operator=(const NewNodeSites&) = delete;

  const std::vector<NewNodeSite>& sites() const { return sites_; }
  /// The site nearest to p and its distance. Precondition: !sites().empty().
  const NewNodeSite& nearest(const std::array<double, 3>& p, double& distance) const;

 private:
  std::vector<NewNodeSite> sites_;
  std::vector<std::array<double, 3>> points_;  ///< of the sites, for the search
  std::optional<NearestPoint> search_;         ///< over points_
};

/// A new node that joins a region, and the old member whose data it takes.
struct RegionMember {
  Id node = 0;
  Id source = 0;
  double distance = 0.0;  ///< from the new node to the source
  Id part = 0;
  /// hostShells: the share of the new shell's area that lies on the source shell (0..1], and
  /// whether the source is the shell most of it lies on (the lowest ID among equal shares).
  double share = 1.0;
  bool mainHost = true;
};

/// The new nodes that cover the region of the old nodes `members`: a new node joins when the old
/// shell it lies on has all its corners in the region, or it lies on an edge of that shell whose
/// two ends are members, or on a member corner; its source is the nearest of those members.
/// A removed member on no such shell or edge (an isolated point of the list) gives the nearest
/// new node. Sorted by node ID, each node once.
/// @param nodeIndex  the model's index of node IDs (FeModel::nodeIndex)
/// @param oldShells  the old shells of the remeshed parts (to find the isolated members)
/// @param removed    the members that are no nodes of the new deck
std::vector<RegionMember> regionMembers(const NewNodeSites& sites,
                                        const std::unordered_set<Id>& members, const FeModel& model,
                                        const std::unordered_map<Id, std::size_t>& nodeIndex,
                                        const std::vector<Shell>& oldShells,
                                        const std::unordered_set<Id>& removed);

/// Per new shell (IDs from `firstNew` in mesh and face order, as replacePartMeshes numbers
/// them), the old shells of its part it lies on: 16 points spread evenly over it each take the
/// closest old shell; per old shell one member, `node` the new shell's ID, `source` the old
/// one's, `share` the share of the points on it, `distance` the least from a point to it. In new
/// shell order, then ascending old shell ID.
std::vector<RegionMember> hostShells(const FeModel& model, const std::vector<QuadMesh>& meshes,
                                     Id firstNew);

/// The new shells that join a shell set: those whose main host (hostShells) is a member of the
/// set named by `references` (one list's Member references), each once, sorted by ID, with that
/// member as source.
std::vector<RegionMember> shellSetMembers(const std::vector<RegionMember>& hosts,
                                          const std::vector<const NodeReference*>& references);

/// The edits that make one block's references of one region role cover the new members: a
/// Member list gets the new IDs in the fields of its removed members (blanked when left over)
/// and in lines added after its last reference; a Record line is repeated for each new node whose
/// source is its node (and dropped when that node is removed). A record with scaled fields (a
/// pressure) is repeated for every member with its source, those fields multiplied by the
/// member's share (so that the total load stays); one without, for the main hosts only.
/// @param text        the block's text
/// @param references  the block's references of that role (in text order)
/// @param removed     the referenced nodes that are no nodes of the new deck
std::vector<TextEdit> regionEdits(std::string_view text,
                                  const std::vector<const NodeReference*>& references,
                                  const std::vector<RegionMember>& added,
                                  const std::unordered_set<Id>& removed);

}  // namespace voxremesh::assembly
