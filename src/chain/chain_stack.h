// Helpers the chain's actions share: finding items on the stack and reporting (action_chain.h).
#pragma once

#include <stdexcept>
#include <string>

#include "voxremesh/action_chain.h"
#include "voxremesh/errors.h"

namespace voxremesh::chain::detail {

/// "deck", "quad mesh" or "volume".
inline const char* kindName(ChainItem::Kind kind) {
  switch (kind) {
    case ChainItem::Kind::Deck:
      return "deck";
    case ChainItem::Kind::Mesh:
      return "quad mesh";
    case ChainItem::Kind::Volume:
      break;
  }
  return "volume";
}

/// The topmost item of a kind. Throws std::runtime_error when the stack has none.
inline ChainItem& topOf(ChainState& state, ChainItem::Kind kind) {
  for (auto it = state.stack.rbegin(); it != state.stack.rend(); ++it)
    if (it->kind == kind) return *it;
  throw std::runtime_error(std::string("needs a ") + kindName(kind) +
                           " on the stack; read or make one first");
}

/// The top item. Throws std::runtime_error when the stack is empty.
inline ChainItem& top(ChainState& state) {
  if (state.stack.empty()) throw std::runtime_error("the stack is empty; read something first");
  return state.stack.back();
}

/// Hands text to the state's print callback (if any).
inline void say(const ChainState& state, const std::string& text) {
  if (state.print) state.print(text);
}

/// Hands warnings to the state's warn callback (if any).
inline void warnAll(const ChainState& state, const Warnings& warnings) {
  if (!state.warn) return;
  for (const std::string& warning : warnings) state.warn(warning);
}

/// The quads and triangles of a mesh as "P points, Q quads, T triangles".
inline std::string meshCounts(const QuadMesh& mesh) {
  std::size_t quads = 0;
  for (const auto& face : mesh.faces) quads += cornerCount(face) == 4 ? 1 : 0;
  return std::to_string(mesh.points.size()) + " points, " + std::to_string(quads) + " quads, " +
         std::to_string(mesh.faces.size() - quads) + " triangles";
}

/// -optimize: optimizeQuadMesh on the topmost quad mesh (chain_mesh_actions.cpp).
void runOptimize(ChainState& state, const ActionCall& call);
/// -quality: assessQuality of the topmost quad mesh or deck (chain_mesh_actions.cpp).
void runQuality(ChainState& state, const ActionCall& call);

}  // namespace voxremesh::chain::detail
