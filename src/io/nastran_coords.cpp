// Nastran coordinate systems (see nastran_coords.h).
#include "io/nastran_coords.h"

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "geometry/vec3.h"
#include "voxremesh/errors.h"

namespace voxremesh::io::nastran {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kDegree = M_PI / 180.0;

/// The frame of a card whose reference system is already resolved (`reference`, null for the
/// basic system).
CoordFrame frameOf(Id id, const CoordCard& card, const CoordFrame* reference) {
  Vec3 a = card.a, b = card.b, c = card.c;
  if (reference != nullptr) {
    a = toBasic(*reference, a);
    b = toBasic(*reference, b);
    c = toBasic(*reference, c);
  }
  const Vec3 z = b - a;
  const Vec3 y = cross(z, c - a);
  if (!(norm(z) > 0.0) || !(norm(y) > 1e-12 * norm(z) * norm(c - a)))
    throw InputError(card.file, card.line,
                     std::string("CORD2") + card.type + " " + std::to_string(id) +
                         ": its points A, B and C do not define axes (A = B, or C on the line "
                         "A-B)",
                     card.text);
  CoordFrame frame;
  frame.type = card.type;
  frame.origin = a;
  frame.axes[2] = normalized(z);
  frame.axes[1] = normalized(y);
  frame.axes[0] = cross(frame.axes[1], frame.axes[2]);
  return frame;
}

/// Resolves system `id` and the chain of systems it refers to (iteratively: a chain may be long)
/// into `frames`.
void resolve(Id id, const std::map<Id, CoordCard>& cards, std::map<Id, CoordFrame>& frames) {
  std::vector<Id> chain;  // from `id` down to the first system already resolved or on basic
  std::set<Id> seen;
  for (Id at = id; at != 0 && frames.count(at) == 0;) {
    const CoordCard& card = cards.at(at);
    const std::string what = std::string("CORD2") + card.type + " " + std::to_string(at);
    if (!seen.insert(at).second)
      throw InputError(card.file, card.line,
                       what + ": its chain of reference systems (RID) returns to itself",
                       card.text);
    chain.push_back(at);
    if (card.rid != 0 && cards.count(card.rid) == 0)
      throw InputError(card.file, card.line,
                       what + " refers to coordinate system " + std::to_string(card.rid) +
                           ", which the deck does not define by a CORD2R, CORD2C or CORD2S card",
                       card.text);
    at = card.rid;
  }
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const CoordCard& card = cards.at(*it);
    const CoordFrame* reference = card.rid == 0 ? nullptr : &frames.at(card.rid);
    frames.emplace(*it, frameOf(*it, card, reference));
  }
}

}  // namespace

std::map<Id, CoordFrame> resolveCoordFrames(const std::map<Id, CoordCard>& cards) {
  std::map<Id, CoordFrame> frames;
  for (const auto& entry : cards) resolve(entry.first, cards, frames);
  return frames;
}

std::array<double, 3> toBasic(const CoordFrame& frame, const std::array<double, 3>& local) {
  Vec3 xyz = local;
  if (frame.type == 'C') {
    const double r = local[0], theta = local[1] * kDegree;
    xyz = {r * std::cos(theta), r * std::sin(theta), local[2]};
  } else if (frame.type == 'S') {
    const double r = local[0], theta = local[1] * kDegree, phi = local[2] * kDegree;
    xyz = {r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
           r * std::cos(theta)};
  }
  return frame.origin + frame.axes[0] * xyz[0] + frame.axes[1] * xyz[1] + frame.axes[2] * xyz[2];
}

}  // namespace voxremesh::io::nastran
