// Regions named by node lists and per-node data, carried over to the new meshes (node_regions.h).
#include "assembly/node_regions.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "geometry/vec3.h"
#include "io/nastran_cards.h"
#include "io/text_scan.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::assembly {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The old shells of a part as a surface to search, with the shell of each of its faces.
struct OldPartSurface {
  std::vector<const Shell*> shells;
  ReferenceSurface surface;
};

OldPartSurface oldPartSurface(const FeModel& model, Id part) {
  OldPartSurface old{{}, ReferenceSurface(quadMeshFromModel(model, part))};
  for (const Shell& shell : model.shells)
    if (shell.part == part) old.shells.push_back(&shell);
  return old;
}

}  // namespace

NewNodeSites::NewNodeSites(const FeModel& model, const std::vector<QuadMesh>& meshes,
                           const std::vector<std::vector<Id>>& pointIds, Id firstNew) {
  std::unordered_set<Id> located;
  const std::unordered_map<Id, std::size_t> nodeIndex = model.nodeIndex();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    std::vector<Vec3> queries;
    std::vector<Id> ids;
    for (std::size_t p = 0; p < meshes[m].points.size(); ++p) {
      const Id id = pointIds[m][p];
      if (id < firstNew || !located.insert(id).second) continue;
      queries.push_back(meshes[m].points[p]);
      ids.push_back(id);
    }
    if (queries.empty()) continue;
    const OldPartSurface old = oldPartSurface(model, meshes[m].part);
    if (old.surface.empty()) continue;
    const std::vector<SurfaceHit> hits = old.surface.closestPoints(queries);
    for (std::size_t q = 0; q < queries.size(); ++q) {
      NewNodeSite site;
      site.node = ids[q];
      site.part = meshes[m].part;
      site.xyz = queries[q];
      site.onOld = hits[q].point;
      const Shell& shell = *old.shells[hits[q].face];
      site.cornerCount = shell.nodeCount;
      for (int c = 0; c < shell.nodeCount; ++c) {
        site.corners[std::size_t(c)] = shell.nodes[std::size_t(c)];
        site.cornerXyz[std::size_t(c)] = model.nodes[nodeIndex.at(shell.nodes[std::size_t(c)])].xyz;
      }
      sites_.push_back(site);
      points_.push_back(site.xyz);
    }
  }
  search_.emplace(points_);
}

const NewNodeSite& NewNodeSites::nearest(const std::array<double, 3>& p, double& distance) const {
  return sites_[search_->nearest(p, &distance)];
}

namespace {

/// The number of points facePoints spreads over a face.
constexpr std::size_t kFacePoints = 16;

/// kFacePoints points spread evenly over a face: a 4 x 4 grid of cell centres in its parameters
/// (a quad), or the centroids of its 16 triangles when cut into four along each side (a
/// triangle: barycentric (i, j, k) + 1/3 with i + j + k = 3, and + 2/3 with i + j + k = 2).
void facePoints(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                std::vector<Vec3>& out) {
  const auto p = [&](int c) { return mesh.points[face[std::size_t(c)]]; };
  if (cornerCount(face) == 4) {
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const double u = (i + 0.5) / 4, v = (j + 0.5) / 4;
        out.push_back(p(0) * ((1 - u) * (1 - v)) + p(1) * (u * (1 - v)) + p(2) * (u * v) +
                      p(3) * ((1 - u) * v));
      }
    return;
  }
  for (const auto& [sum, offset] : {std::pair<int, double>{3, 1.0 / 3}, {2, 2.0 / 3}})
    for (int i = 0; i <= sum; ++i)
      for (int j = 0; i + j <= sum; ++j)
        out.push_back(p(0) * ((i + offset) / 4) + p(1) * ((j + offset) / 4) +
                      p(2) * ((sum - i - j + offset) / 4));
}

}  // namespace

std::vector<RegionMember> hostShells(const FeModel& model, const std::vector<QuadMesh>& meshes,
                                     Id firstNew) {
  std::vector<RegionMember> hosts;
  Id next = firstNew;
  std::vector<Vec3> points;
  for (const QuadMesh& mesh : meshes) {
    const OldPartSurface old = oldPartSurface(model, mesh.part);
    if (old.surface.empty() || mesh.faces.empty()) {
      next += Id(mesh.faces.size());
      continue;
    }
    points.clear();
    for (const auto& face : mesh.faces) facePoints(mesh, face, points);
    const std::vector<SurfaceHit> hits = old.surface.closestPoints(points);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f, ++next) {
      std::map<Id, std::pair<std::size_t, double>> onShell;  // old shell -> (points, distance)
      for (std::size_t s = f * kFacePoints; s < (f + 1) * kFacePoints; ++s) {
        auto [it, inserted] =
            onShell.try_emplace(old.shells[hits[s].face]->id, 0, hits[s].distance);
        ++it->second.first;
        it->second.second = std::min(it->second.second, hits[s].distance);
      }
      auto main = onShell.begin();  // the most points; the lowest ID among equals
      for (auto it = onShell.begin(); it != onShell.end(); ++it)
        if (it->second.first > main->second.first) main = it;
      for (const auto& [shell, counts] : onShell)
        hosts.push_back(RegionMember{next, shell, counts.second, mesh.part,
                                     double(counts.first) / kFacePoints, shell == main->first});
    }
  }
  return hosts;
}

namespace {

/// The distance from p to the segment a-b.
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = geom::dot(ab, ab);
  const double t = length2 > 0 ? std::clamp(geom::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return geom::distance(p, a + ab * t);
}

/// Where a site joins the region: the source member, or 0 when it does not join.
Id siteSource(const NewNodeSite& site, const std::unordered_set<Id>& members) {
  const int n = site.cornerCount;
  double longest = 0;
  for (int c = 0; c < n; ++c)
    longest = std::max(longest, geom::distance(site.cornerXyz[std::size_t(c)],
                                               site.cornerXyz[std::size_t((c + 1) % n)]));
  const double tolerance = 1e-6 * longest;
  // The nearest corner among those allowed.
  const auto nearest = [&](auto allowed) {
    Id best = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int c = 0; c < n; ++c) {
      if (!allowed(c)) continue;
      const double d = geom::distance(site.onOld, site.cornerXyz[std::size_t(c)]);
      const Id id = site.corners[std::size_t(c)];
      if (d < bestDistance || (d == bestDistance && id < best)) {
        bestDistance = d;
        best = id;
      }
    }
    return best;
  };
  const auto member = [&](int c) { return members.count(site.corners[std::size_t(c)]) > 0; };
  bool all = true;
  for (int c = 0; c < n; ++c) all = all && member(c);
  if (all) return nearest([](int) { return true; });
  for (int c = 0; c < n; ++c) {
    const int d = (c + 1) % n;
    if (member(c) && member(d) &&
        segmentDistance(site.onOld, site.cornerXyz[std::size_t(c)],
                        site.cornerXyz[std::size_t(d)]) <= tolerance)
      return nearest([&](int k) { return k == c || k == d; });
  }
  return nearest([&](int c) {
    return member(c) && geom::distance(site.onOld, site.cornerXyz[std::size_t(c)]) <= tolerance;
  });
}

/// The removed members on no old shell whose corners are all members and on no edge whose ends
/// are (ascending).
std::vector<Id> isolatedMembers(const std::vector<Shell>& oldShells,
                                const std::unordered_set<Id>& members,
                                const std::unordered_set<Id>& removed) {
  std::unordered_set<Id> covered;
  for (const Shell& shell : oldShells) {
    const int n = shell.nodeCount;
    for (int c = 0; c < n; ++c) {
      const Id a = shell.nodes[std::size_t(c)], b = shell.nodes[std::size_t((c + 1) % n)];
      if (members.count(a) && members.count(b)) {
        covered.insert(a);
        covered.insert(b);
      }
    }
  }
  std::vector<Id> isolated;
  for (const Id node : members)
    if (removed.count(node) && !covered.count(node)) isolated.push_back(node);
  std::sort(isolated.begin(), isolated.end());
  return isolated;
}

}  // namespace

std::vector<RegionMember> regionMembers(const NewNodeSites& sites,
                                        const std::unordered_set<Id>& members, const FeModel& model,
                                        const std::unordered_map<Id, std::size_t>& nodeIndex,
                                        const std::vector<Shell>& oldShells,
                                        const std::unordered_set<Id>& removed) {
  std::map<Id, RegionMember> joined;
  for (const NewNodeSite& site : sites.sites()) {
    const Id source = siteSource(site, members);
    if (source == 0) continue;
    joined[site.node] =
        RegionMember{site.node, source,
                     geom::distance(site.xyz, model.nodes[nodeIndex.at(source)].xyz), site.part};
  }
  // Isolated members give their nearest new node; so do all removed ones when no new node
  // joined (a line of nodes the new mesh has no node on), so that no region is lost.
  std::vector<Id> isolated = isolatedMembers(oldShells, members, removed);
  if (joined.empty()) {
    isolated.clear();
    for (const Id node : members)
      if (removed.count(node)) isolated.push_back(node);
    std::sort(isolated.begin(), isolated.end());
  }
  if (!sites.sites().empty())
    for (const Id node : isolated) {
      double distance = 0;
      const NewNodeSite& site = sites.nearest(model.nodes[nodeIndex.at(node)].xyz, distance);
      joined.emplace(site.node, RegionMember{site.node, node, distance, site.part});
    }
  std::vector<RegionMember> result;
  result.reserve(joined.size());
  for (const auto& entry : joined) result.push_back(entry.second);
  return result;
}

namespace {

/// The text of a node ID in a reference's field: right-aligned in its width, or the number.
std::string fieldText(const NodeReference& reference, Id id) {
  std::string text;
  if (!referenceText(reference, id, text)) text = std::to_string(id);
  return text;
}

/// The span [begin, end) of the line around `offset` in text, its line break included.
std::pair<std::size_t, std::size_t> lineAround(std::string_view text, std::size_t offset) {
  const std::size_t before = offset == 0 ? std::string_view::npos : text.rfind('\n', offset - 1);
  const std::size_t begin = before == std::string_view::npos ? 0 : before + 1;
  const std::size_t after = text.find('\n', offset);
  return {begin, after == std::string_view::npos ? text.size() : after + 1};
}

/// A list's extra data lines: the IDs `perLine` to a line after the list's line prefix, in the
/// reference's field width (or separated by commas in free format), each line ending as
/// `lineEnd`.
std::string listLines(const NodeReference& like, const std::vector<Id>& ids,
                      std::string_view lineEnd) {
  std::string out;
  const std::size_t perLine = std::max<std::size_t>(like.perLine, 1);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i % perLine == 0) out += like.linePrefix;
    if (like.width == 0 && i % perLine != 0) out += ',';
    out += fieldText(like, ids[i]);
    if (i % perLine == perLine - 1 || i + 1 == ids.size()) out += lineEnd;
  }
  return out;
}

/// A real field's value times `factor`, in the field's width (a free-format token: shortest).
/// A field that does not read as a real stays as it is.
std::string scaledField(std::string_view field, std::size_t width, double factor) {
  double value = 0.0;
  if (!io::parseReal(field, value)) return std::string(field);
  std::string text;
  if (width == 0) {
    io::appendShortest(text, value * factor);
    return text;
  }
  io::nastran::appendReal(text, value * factor, static_cast<int>(width));
  return text;
}

/// `text` with the edits (offsets into it, not overlapping) applied.
std::string withEdits(std::string_view text, std::vector<TextEdit> edits) {
  std::sort(edits.begin(), edits.end(),
            [](const TextEdit& a, const TextEdit& b) { return a.offset > b.offset; });
  std::string out(text);
  for (const TextEdit& edit : edits) out.replace(edit.offset, edit.length, edit.text);
  return out;
}

}  // namespace

std::vector<RegionMember> shellSetMembers(const std::vector<RegionMember>& hosts,
                                          const std::vector<const NodeReference*>& references) {
  std::unordered_set<Id> members;
  for (const NodeReference* reference : references) members.insert(reference->node);
  std::vector<RegionMember> joined;
  for (const RegionMember& host : hosts)
    if (host.mainHost && members.count(host.source)) joined.push_back(host);
  std::sort(joined.begin(), joined.end(),
            [](const RegionMember& a, const RegionMember& b) { return a.node < b.node; });
  joined.erase(
      std::unique(joined.begin(), joined.end(),
                  [](const RegionMember& a, const RegionMember& b) { return a.node == b.node; }),
      joined.end());
  return joined;
}

std::vector<TextEdit> regionEdits(std::string_view text,
                                  const std::vector<const NodeReference*>& references,
                                  const std::vector<RegionMember>& added,
                                  const std::unordered_set<Id>& removed) {
  std::vector<TextEdit> edits;
  if (references.empty()) return edits;
  if (references.front()->role == NodeRole::Record) {
    std::unordered_map<Id, std::vector<const RegionMember*>> newOf;  // source -> its members
    for (const RegionMember& member : added) newOf[member.source].push_back(&member);
    std::set<std::pair<Id, std::size_t>> written;  // (node, group): a record repeated once
    for (const NodeReference* reference : references) {
      const bool oneLine = reference->recordFirst == 0 && reference->recordLast == 0;
      const std::size_t begin =
          lineAround(text, oneLine ? reference->offset : reference->recordFirst).first;
      const std::size_t end =
          lineAround(text, oneLine ? reference->offset : reference->recordLast).second;
      const std::string_view line = text.substr(begin, end - begin);
      const std::size_t at = reference->offset - begin;
      std::string out;
      if (!removed.count(reference->node)) out += line;
      const auto found = newOf.find(reference->node);
      if (found != newOf.end() && written.emplace(reference->node, reference->group).second)
        for (const RegionMember* member : found->second) {
          const bool scaled = !reference->scaledFields.empty();
          if (!scaled && !member->mainHost) continue;
          std::vector<TextEdit> fields{
              {at, reference->length, fieldText(*reference, member->node)}};
          if (scaled && member->share != 1.0)
            for (const BlockField& span : reference->scaledFields)
              fields.push_back({span.offset - begin, span.length,
                                scaledField(line.substr(span.offset - begin, span.length),
                                            span.width, member->share)});
          out += withEdits(line, fields);
        }
      edits.push_back(TextEdit{begin, end - begin, std::move(out)});
    }
    return edits;
  }
  // A list: new IDs first into the fields of removed members, the rest in lines after the last;
  // a field left over is blank, or where blanks are not read, repeats a member.
  Id repeated = added.empty() ? 0 : added.front().node;
  for (const NodeReference* reference : references)
    if (repeated == 0 && !removed.count(reference->node)) repeated = reference->node;
  std::size_t next = 0;
  for (const NodeReference* reference : references) {
    if (!removed.count(reference->node)) continue;
    std::string field = next < added.size() ? fieldText(*reference, added[next++].node)
                        : reference->blankAllowed || repeated == 0
                            ? std::string(reference->width, ' ')
                            : fieldText(*reference, repeated);
    edits.push_back(TextEdit{reference->offset, reference->length, std::move(field)});
  }
  if (next < added.size()) {
    const NodeReference& last = *references.back();
    const auto [begin, end] = lineAround(text, last.listLast);
    std::string_view lineEnd = "\n";
    if (end >= begin + 2 && text.substr(end - 2, 2) == "\r\n") lineEnd = "\r\n";
    std::vector<Id> rest;
    for (std::size_t i = next; i < added.size(); ++i) rest.push_back(added[i].node);
    std::string lines = listLines(last, rest, lineEnd);
    if (end == text.size() && (end == begin || text[end - 1] != '\n'))
      lines.insert(0, std::string(lineEnd));
    edits.push_back(TextEdit{end, 0, std::move(lines)});
  }
  return edits;
}

}  // namespace voxremesh::assembly
