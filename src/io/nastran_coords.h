// Nastran coordinate systems defined by three points (CORD2R, CORD2C, CORD2S), so that GRIDs given
// in a local system (CP) are read into the basic system. Definitions as in the MSC Nastran Quick
// Reference Guide: A is the origin, A->B the z axis, C lies in the x-z plane; A, B and C are given
// in the reference system RID (0: basic). Local coordinates are (x, y, z) in a rectangular system,
// (r, theta, z) in a cylindrical one and (r, theta, phi) in a spherical one, angles in degrees.
#pragma once

#include <array>
#include <map>
#include <string>

#include "voxremesh/fe_model.h"

namespace voxremesh::io::nastran {

/// A CORD2R/CORD2C/CORD2S card as read, with where it stood (for messages).
struct CoordCard {
  char type = 'R';  ///< 'R', 'C' or 'S'
  Id rid = 0;
  std::array<double, 3> a{}, b{}, c{};
  std::string file;
  std::size_t line = 0;
  std::string text;  ///< the card's first line
};

/// A resolved system: its kind, origin and unit axes in the basic system.
struct CoordFrame {
  char type = 'R';
  std::array<double, 3> origin{};
  std::array<std::array<double, 3>, 3> axes{};  ///< x, y, z
};

/// Resolves every card into the basic system, following RID chains.
/// @param cards  the systems by ID (ID > 0)
/// Throws InputError naming a card's file and line when its RID is not defined, a chain of RIDs
/// returns to itself, or its three points do not define axes (A = B, or C on the z axis).
std::map<Id, CoordFrame> resolveCoordFrames(const std::map<Id, CoordCard>& cards);

/// The basic coordinates of a point given in `frame`'s local coordinates (see the top).
std::array<double, 3> toBasic(const CoordFrame& frame, const std::array<double, 3>& local);

}  // namespace voxremesh::io::nastran
