// remeshDeck: the stages composed over the parts of a deck (pipeline.h).
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <unordered_map>

#include <unordered_set>
#include "voxremesh/reference_surface.h"

#include "io/atomic_file.h"
#include "json/json.h"
#include "voxremesh/errors.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh {

namespace {

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Rethrows `error` with "part ID: " before its message, keeping InputError and SettingError.
[[noreturn]] void rethrowForPart(const std::exception_ptr& error, Id part) {
  const std::string prefix = "part " + std::to_string(part) + ": ";
  try {
    std::rethrow_exception(error);
  } catch (const InputError&) {
    throw;
  } catch (const SettingError& e) {
    throw SettingError(prefix + e.what());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(prefix + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error(prefix + e.what());
  }
}

/// For each plan, a model holding the part's shells plus the shells of other parts that share a
/// node with it (so that buildSheets still finds the seams), and the nodes they use: sheets and
/// volumes then cost what the part costs, not what the deck costs. `junctionSpacing` receives per
/// plan the smallest target size among it and the planned parts it shares nodes with, so that
/// both sides of a seam place the same nodes on it.
std::vector<FeModel> partModels(const FeModel& deck, const std::vector<PartPlan>& plans,
                                std::vector<double>& junctionSpacing) {
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
  junctionSpacing.resize(plans.size());
  for (std::size_t i = 0; i < plans.size(); ++i) junctionSpacing[i] = plans[i].targetSize;
  for (const auto& [node, list] : plansOfNode) {
    if (list.size() < 2) continue;
    double smallest = junctionSpacing[list[0]];
    for (const std::size_t plan : list) smallest = std::min(smallest, plans[plan].targetSize);
    for (const std::size_t plan : list)
      junctionSpacing[plan] = std::min(junctionSpacing[plan], smallest);
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
  for (FeModel& model : models) {
    std::unordered_set<Id> used;
    for (const Shell& shell : model.shells)
      for (int c = 0; c < shell.nodeCount; ++c)
        if (used.insert(shell.nodes[static_cast<std::size_t>(c)]).second)
          model.nodes.push_back(deck.nodes[nodeIndex.at(shell.nodes[static_cast<std::size_t>(c)])]);
  }
  return models;
}

/// The faces of a sheet as a mesh, the surface its new mesh is projected on.
QuadMesh sheetSurface(const Sheet& sheet) {
  QuadMesh mesh;
  mesh.part = sheet.part;
  mesh.points = sheet.points;
  mesh.faces.reserve(sheet.faces.size());
  for (const auto& face : sheet.faces)
    mesh.faces.push_back({face[0], face[1], face[2], face[3] == kNoPoint ? kNoCorner : face[3]});
  return mesh;
}

}  // namespace

RemeshReport remeshDeck(FeModel& deck, const RemeshSettings& settings,
                        const RemeshProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  RemeshReport report;
  const std::vector<PartPlan> plans = planRemesh(deck, settings);
  report.parts.resize(plans.size());
  std::vector<double> junctionSpacing;
  const std::vector<FeModel> models = partModels(deck, plans, junctionSpacing);
  std::vector<QuadMesh> meshes(plans.size());
  std::vector<std::exception_ptr> errors(plans.size());
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
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
      RemeshedPart& part = report.parts[i];
      part.plan = plans[i];
      try {
        tell("volume", plans[i].part, false);
        auto stageStart = std::chrono::steady_clock::now();
        const std::vector<SheetVolume> volumes = partVolumes(models[i], plans[i], settings);
        part.volumeSeconds = since(stageStart);
        std::vector<QuadMesh> sheetMeshes;
        for (const SheetVolume& sheet : volumes) {
          tell("extract", plans[i].part, false);
          stageStart = std::chrono::steady_clock::now();
          ExtractStats stats;
          ExtractSettings extractSettings = settings.extract;
          if (extractSettings.junctionSpacing <= 0.0)
            extractSettings.junctionSpacing = junctionSpacing[i];
          sheetMeshes.push_back(extractQuadMesh(sheet.volume, extractSettings, &stats));
          addExtractStats(part.extract, stats);
          part.extractSeconds += since(stageStart);
          if (settings.optimize) {
            tell("optimize", plans[i].part, false);
            stageStart = std::chrono::steady_clock::now();
            const ReferenceSurface original(sheetSurface(sheet.sheet));
            OptimizeSettings optimizeSettings = settings.optimizeSettings;
            optimizeSettings.quality.targetSize = plans[i].targetSize;
            optimizeQuadMesh(sheetMeshes.back(), original, optimizeSettings);
            part.optimizeSeconds += since(stageStart);
          }
        }
        meshes[i] = joinAtJunctions(sheetMeshes);
        meshes[i].part = plans[i].part;
        for (const auto& face : meshes[i].faces)
          (cornerCount(face) == 4 ? part.quads : part.trias)++;
      } catch (...) {
        errors[i] = std::current_exception();
      }
      tell("extract", plans[i].part, true);
    });
  });
  for (std::size_t i = 0; i < plans.size(); ++i)
    if (errors[i]) rethrowForPart(errors[i], plans[i].part);
  if (progress) progress("assemble", 0, 1.0);
  const auto assemblyStart = std::chrono::steady_clock::now();
  report.assembly = replacePartMeshes(deck, meshes);
  report.assemblySeconds = since(assemblyStart);
  report.totalSeconds = since(start);
  return report;
}

std::string remeshReportJson(const RemeshReport& report) {
  std::string out = "{\n  \"parts\": [";
  char buffer[512];
  for (std::size_t i = 0; i < report.parts.size(); ++i) {
    const RemeshedPart& part = report.parts[i];
    std::snprintf(buffer, sizeof buffer,
                  "%s\n    {\"part\": %lld, \"elements_before\": %zu, \"quads\": %zu, "
                  "\"trias\": %zu, \"target_size\": %.17g, \"volume_seconds\": %.6f, "
                  "\"extract_seconds\": %.6f}",
                  i ? "," : "", static_cast<long long>(part.plan.part), part.plan.shells,
                  part.quads, part.trias, part.plan.targetSize, part.volumeSeconds,
                  part.extractSeconds);
    out += buffer;
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
    std::snprintf(buffer, sizeof buffer, "%s\n    {\"keyword\": %s, \"line\": %zu, \"node\": %lld}",
                  i ? "," : "", json::quote(ref.keyword).c_str(), ref.line,
                  static_cast<long long>(ref.node));
    out += buffer;
  }
  std::snprintf(
      buffer, sizeof buffer,
      "\n  ],\n  \"removed_nodes\": %zu,\n  \"new_nodes\": %zu,\n  \"seconds\": %.6f\n}\n",
      assembly.removedNodes, assembly.newNodes, report.totalSeconds);
  return out + buffer;
}

void writeRemeshReport(const RemeshReport& report, const std::filesystem::path& path) {
  io::writeFileAtomically(path, remeshReportJson(report));
}

}  // namespace voxremesh
