// Nastran coordinate systems (see nastran_coords.h).
#include "io/nastran_coords.h"

#include <cmath>
#include <set>

#include "geometry/vec3.h"
#include "voxremesh/errors.h"

namespace voxremesh::io::nastran {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kDegree = M_PI / 180.0;

/// Resolves system `id` (and the systems it refers to) into `frames`; `open` holds the systems
/// being resolved, to find cycles.
const CoordFrame& resolve(Id id, const std::map<Id, CoordCard>& cards,
                          std::map<Id, CoordFrame>& frames, std::set<Id>& open) {
  if (const auto done = frames.find(id); done != frames.end()) return done->second;
  const CoordCard& card = cards.at(id);
  const std::string what = std::string("CORD2") + card.type + " " + std::to_string(id);
  if (!open.insert(id).second)
    throw InputError(card.file, card.line,
                     what +
                         ": its chain of reference systems (RID) returns "
                         "to itself",
                     card.text);
  Vec3 a = card.a, b = card.b, c = card.c;
  if (card.rid != 0) {
    if (cards.count(card.rid) == 0)
      throw InputError(card.file, card.line,
                       what + " refers to coordinate system " + std::to_string(card.rid) +
                           ", which the deck does not define by a CORD2R, CORD2C or CORD2S card",
                       card.text);
    const CoordFrame& reference = resolve(card.rid, cards, frames, open);
    a = toBasic(reference, a);
    b = toBasic(reference, b);
    c = toBasic(reference, c);
  }
  const Vec3 z = b - a;
  const Vec3 y = cross(z, c - a);
  if (!(norm(z) > 0.0) || !(norm(y) > 1e-12 * norm(z) * norm(c - a)))
    throw InputError(card.file, card.line,
                     what +
                         ": its points A, B and C do not define axes (A = B, or C on the line "
                         "A-B)",
                     card.text);
  CoordFrame frame;
  frame.type = card.type;
  frame.origin = a;
  frame.axes[2] = normalized(z);
  frame.axes[1] = normalized(y);
  frame.axes[0] = cross(frame.axes[1], frame.axes[2]);
  open.erase(id);
  return frames.emplace(id, frame).first->second;
}

}  // namespace

std::map<Id, CoordFrame> resolveCoordFrames(const std::map<Id, CoordCard>& cards) {
  std::map<Id, CoordFrame> frames;
  for (const auto& [id, card] : cards) {
    std::set<Id> open;
    resolve(id, cards, frames, open);
  }
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
