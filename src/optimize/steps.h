// The optimisation steps that read a whole mesh's topology or failures, with the cache
// optimizeQuadMesh shares between them (mesh_cache.h): each does what its namesake in optimize.h
// does (that one keeps a cache of its own) and takes what the cache still holds of the mesh.
// The cache's settings are the criteria the step is given, where it is given any.
#pragma once

#include "optimize/mesh_cache.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

/// cleanUpMesh (optimize.h) with a shared cache.
CleanupResult cleanUpMesh(QuadMesh& mesh, const CleanupSettings& settings, opt::MeshCache& cache);

/// collapseRhombicQuads (optimize.h) with a shared cache.
std::size_t collapseRhombicQuads(QuadMesh& mesh, const ReferenceSurface* surface,
                                 opt::MeshCache& cache);

/// relaxMesh (optimize.h) with a shared cache.
void relaxMesh(QuadMesh& mesh, const ReferenceSurface& original, int iterations, double damping,
               double targetSize, opt::MeshCache& cache);

/// mergeTrianglePairs (optimize.h) with a shared cache.
std::size_t mergeTrianglePairs(QuadMesh& mesh, const QualitySettings& settings,
                               opt::MeshCache& cache);

/// improveFailingElements (optimize.h) with a shared cache.
std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps,
                                   opt::MeshCache& cache);

/// reconnectFailingFaces (optimize.h) with a shared cache.
std::size_t reconnectFailingFaces(QuadMesh& mesh, const ReferenceSurface& original,
                                  const QualitySettings& settings,
                                  const ReconnectSettings& reconnect, opt::MeshCache& cache);

/// removeWarping (optimize.h) with a shared cache.
WarpingResult removeWarping(QuadMesh& mesh, double maxWarpingDeg, int maxIterations, double maxMove,
                            opt::MeshCache& cache);

/// refillFoldedRegions (optimize.h) with a shared cache.
std::size_t refillFoldedRegions(QuadMesh& mesh, const ReferenceSurface& original,
                                const QualitySettings& settings, opt::MeshCache& cache);

/// fitFarOriginalPoints (optimize.h) with a shared cache.
std::size_t fitFarOriginalPoints(QuadMesh& mesh, const ReferenceSurface& original,
                                 const QualitySettings& settings, int maxPasses,
                                 opt::MeshCache& cache);

}  // namespace voxremesh
