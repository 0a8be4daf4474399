// Deck assembly: putting remeshed parts back into the deck they came from.
//
// replacePartMeshes replaces the shells of each remeshed part by the faces of its new mesh and
// keeps everything else of the deck: the other parts, every other element type and keyword.
//
// Definitions
// - Remeshed parts: the parts of the given meshes (QuadMesh::part). Kept shells: the shells of
//   every other part; kept-shell nodes: the nodes they use.
// - Old nodes: the nodes used by shells of remeshed parts but by no kept shell. They are removed
//   unless a keyword still names them after remapping (see below).
// - New node IDs: points of the meshes in mesh order, then point order, get consecutive IDs from
//   one above the largest node ID of the input deck (removed nodes included, so that a stale
//   reference can never name a new node). Two points become one node when
//   (a) a point has bit-identical coordinates to a kept-shell node that its part's old shells
//       used (a seam node): it takes that node's ID (the lowest ID when several such nodes share
//       the coordinates), so a seam with a part that is not remeshed stays conforming, while a
//       node of another part that only coincides with the new point (joined by a rigid element
//       or a weld, or not at all) stays apart; or
//   (b) two points of meshes of different parts both have PointRole::Junction and bit-identical
//       coordinates: the later one takes the earlier one's node; or
//   (c) a point has bit-identical coordinates to a hard point (an old node that other keywords
//       use as a point, hardPointNodes) of its part: it takes that node's ID, and the node is
//       neither removed nor remapped, so the element, weld or load on it stays where it was.
// - New element IDs: the faces of the meshes in mesh order, then face order, get consecutive IDs
//   from one above the largest element ID of the deck: shells, and the first field of the data
//   lines of verbatim element keywords (LS-DYNA *ELEMENT_..., Nastran C..., RBE..., CONM2,
//   PLOTEL, Abaqus *ELEMENT). A face with kNoCorner fourth corner is a triangle.
// - Element type and extras: a new shell gets the element type most of the part's old shells
//   had (ties: the lower type index). When some old shells of the part had per-element extras
//   (thickness, material angle, offset), each new shell takes those of the old shell whose
//   centroid is nearest to its own centroid (ties: the earlier shell).
// - Order: kept shells keep their order; new shells follow them, in mesh and face order. Kept
//   nodes keep their order; new nodes follow them.
// - Node references: verbatim keywords that name old nodes are rewritten to the nearest new node
//   of a part the old node belonged to (Euclidean distance to the node's point; ties: the lower
//   node ID), each change listed in NodeRemap. The keywords understood field by field:
//     LS-DYNA  *SET_NODE, *SET_NODE_LIST (_TITLE), *DATABASE_HISTORY_NODE (_ID),
//              *CONSTRAINED_SPOTWELD, *CONSTRAINED_NODAL_RIGID_BODY (PNODE),
//              *CONSTRAINED_EXTRA_NODES_NODE, *BOUNDARY_SPC_NODE,
//              *BOUNDARY_PRESCRIBED_MOTION_NODE, *INITIAL_VELOCITY_NODE, *LOAD_NODE_POINT,
//              *ELEMENT_MASS, *ELEMENT_BEAM, *ELEMENT_DISCRETE, *ELEMENT_SPH
//     Nastran  SPC, SPCD, SPC1, SET1, RBE2, RBE3, CONM2, CBUSH, CBAR, CBEAM, CROD, CONROD, CELAS1,
//              CELAS2, CDAMP1, CDAMP2, CWELD (GS, GA, GB), PLOTEL, FORCE, MOMENT, PLOAD4 (G1, G3),
//              CORD1R/C/S, CHEXA, CPENTA, CTETRA, SUPORT, SUPORT1 (grids, not components)
//     Abaqus   *NSET, *BOUNDARY, *CLOAD, *ELEMENT (non-shell types)
//   A rewritten field keeps its columns (fixed format: right-aligned in the field's width;
//   free format: the token replaced); every other byte of the deck stays as it was.
// - Regions: the node lists LS-DYNA *SET_NODE and *SET_NODE_LIST (_TITLE), Nastran SET1 and
//   SPC1 and Abaqus *NSET, and the per-node data lines of *INITIAL_VELOCITY_NODE, name a region,
//   not points. A new node joins a keyword's region when
//   the old shell it lies on (its closest point on the part's old shells) has all corners in the
//   region, or it lies on an edge of that shell whose two ends are in it (a set along a side),
//   or on a corner in it; an old member on no such shell or edge (an isolated node) gives the
//   nearest new node. A list gets the new IDs in the fields of its removed members (left blank
//   when fewer new nodes join) and in lines of the same layout after its last reference; a data
//   line is repeated for every new node whose nearest joining member is its node, and dropped
//   when that node is removed. Nastran lists grow by continuation lines (8 small fields, 4 large
//   ones, or a leading comma in free format), Abaqus lists by lines of at most 16 entries; Abaqus
//   reads no empty entry, so there a field left over repeats a member. When no new node joins
//   a region whose members are all removed, each gives its nearest new node. Each new member is
//   a NodeRemap from that member.
// - Loads on elements: a Nastran PLOAD4 on a removed shell is repeated, continuation lines and
//   all, for every new shell that lies partly on that shell (16 points spread over the new shell
//   each take the closest old shell), with the new shell's ID and its pressures times the share
//   of the new shell on the old one, so that the total force stays; the card on the removed
//   shell is dropped. A card whose pressures cannot be rewritten in place goes whole to the new
//   shells mostly on its shell. A PLOAD4 THRU range is left as it is. An LS-DYNA
//   *LOAD_SHELL_ELEMENT or *DATABASE_HISTORY_SHELL_ID line and an Abaqus *DLOAD line naming a
//   removed shell are repeated for the new shells mostly on it (their values and headings as
//   they are), and dropped.
// - Shell sets: an LS-DYNA *SET_SHELL / *SET_SHELL_LIST (_TITLE) or *DATABASE_HISTORY_SHELL
//   list or an Abaqus *ELSET list naming removed shells lists instead the new shells most of
//   whose area lies on its members (each once), in the fields of the removed members and in
//   lines added after its last one. A GENERATE range covering a removed shell cannot be
//   rewritten: it is an UnmappedReference.
// - Unmapped references: a reference that cannot be rewritten (a range such as *SET_NODE_LIST_
//   GENERATE, SPC1 THRU or *NSET GENERATE covering an old node; a new ID wider than its fixed
//   field; a tab-expanded Nastran field), and any integer equal to an old node ID in keywords
//   that may name nodes but are not understood field by field (LS-DYNA keywords starting with
//   *ELEMENT_, *CONSTRAINED_, *BOUNDARY_, *LOAD_, *INITIAL_, *SET_NODE, *SET_SEGMENT (after its
//   first card, or two with _TITLE: a segment's nodes are not rewritten), *DATABASE_HISTORY_ or
//   containing _NODE, except those naming sets, parts or contacts: a name (without _TITLE or
//   _ID) ending in _SET, _GENERAL or _ADD or holding _SET_, ending in _RIGID, *CONTACT_...,
//   *CONSTRAINED_RIGID_BODIES and the shell keywords read for their shell IDs; Nastran cards
//   starting with C or R, MPC, ASET, OMIT, FORCE1/2, MOMENT1/2, TEMP; Abaqus *EQUATION,
//   *MPC, *INITIAL CONDITIONS, *KINEMATIC COUPLING) is listed in UnmappedReference and its node is
//   kept (detached from the new mesh), never dropped. Such a scan cannot tell a node ID from
//   another number that happens to be equal, so it may list false alarms; it never changes the
//   deck.
#pragma once

#include <cstddef>
#include <string>
#include <unordered_set>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh {

/// One rewritten node reference.
struct NodeRemap {
  std::string keyword;  ///< "*SET_NODE_LIST", "SPC1", "*NSET", ...
  std::string file;     ///< the source file of the keyword's block (empty when not recorded)
  /// The line of the reference: in `file` when the block's location is recorded, else the line
  /// within the block (blockLine says which).
  std::size_t line = 0;
  bool blockLine = false;
  Id oldNode = 0;
  Id newNode = 0;
  Id part = 0;  ///< the remeshed part whose new node was chosen
  double distance = 0.0;
};

/// A reference to an old node that was not rewritten; the node is kept.
struct UnmappedReference {
  std::string keyword;
  std::string file;
  std::size_t line = 0;
  bool blockLine = false;  ///< as NodeRemap::blockLine
  Id node = 0;
  std::string reason;
};

/// Counts of one remeshed part.
struct AssembledPart {
  Id part = 0;
  std::size_t shellsBefore = 0;
  std::size_t shellsAfter = 0;
  std::size_t quadsAfter = 0;
  std::size_t triasAfter = 0;
};

/// What replacePartMeshes did.
struct AssemblyReport {
  std::vector<AssembledPart> parts;  ///< in the order of the meshes
  std::vector<NodeRemap> remaps;     ///< in deck order
  std::vector<UnmappedReference> unmapped;
  std::size_t removedNodes = 0;
  std::size_t keptOldNodes = 0;                ///< old nodes kept for unmapped references
  std::size_t seamPoints = 0;                  ///< points that took a kept-shell node (rule a)
  std::size_t mergedJunctionPoints = 0;        ///< points that took another mesh's node (rule b)
  std::size_t hardPointsKept = 0;              ///< hard points that new points took (rule c)
  std::size_t elementLoadsRewritten = 0;       ///< loads on removed shells given to the new ones
  std::size_t elementSetMembersRewritten = 0;  ///< set members that were removed shells
  std::size_t newNodes = 0;
  Id firstNewNodeId = 0;     ///< 0 when no node was added
  Id firstNewElementId = 0;  ///< 0 when no element was added
};

/// Replaces the shells of each remeshed part by its new mesh (see the definitions at the top of
/// the file).
/// @param model     the deck; node IDs unique, every shell naming existing nodes (as readDeck
///                  ensures); modified in place
/// @param newParts  one mesh per remeshed part, QuadMesh::part naming a part with shells in the
///                  model; faces in range, coordinates finite
/// @param hardPoints  old nodes that keep their ID where a new point of their part lies exactly
///                  on them (rule c); the others of the set are remapped like any old node
/// @return what was replaced, remapped and what could not be remapped
/// Throws std::invalid_argument (the model is then unchanged) when a mesh names part 0, a part
/// without shells or a part twice, has a face corner out of range or a non-finite coordinate,
/// or when a shell names a node the model does not define.
AssemblyReport replacePartMeshes(FeModel& model, const std::vector<QuadMesh>& newParts,
                                 const std::unordered_set<Id>& hardPoints = {});

}  // namespace voxremesh

namespace voxremesh {

/// The nodes among `candidates` that solid elements of the deck's verbatim keywords name:
/// Nastran CHEXA, CPENTA, CTETRA, CPYRAM; LS-DYNA *ELEMENT_SOLID... and *ELEMENT_TSHELL... (their
/// data lines scanned for the IDs, which may count an equal number that is not a node). A shell
/// whose corners are all such nodes lies on a face of the solid mesh. Deterministic.
std::unordered_set<Id> solidElementNodes(const FeModel& model,
                                         const std::unordered_set<Id>& candidates);

/// The nodes among `candidates` that verbatim keywords use as points, in fields understood one by
/// one (see the list at the top of the file): element ends (beams, discrete elements, masses,
/// CBAR, CROD, CBUSH, CONM2, ...), rigid elements and constraints (RBE2, RBE3, spot welds, nodal
/// rigid bodies, extra nodes), point loads and boundary conditions (FORCE, MOMENT, SPC, *CLOAD,
/// *BOUNDARY..., SUPORT, SUPORT1), history nodes and the points of CORD1x systems. Node sets and
/// per-node data (*SET_NODE..., *INITIAL_..., *NSET, SET1, SPC1, ASET1, OMIT1, TEMP) describe
/// regions, not points, and ranges cannot be told apart: neither makes a hard point. Deterministic.
std::unordered_set<Id> hardPointNodes(const FeModel& model,
                                      const std::unordered_set<Id>& candidates);

}  // namespace voxremesh
