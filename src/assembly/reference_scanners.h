// The per-format scanners behind findNodeReferences and maxVerbatimElementId (one .cpp per
// format: lsdyna_references.cpp, nastran_references.cpp, abaqus_references.cpp). Internal to
// src/assembly.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "assembly/node_references.h"
#include "io/lsdyna_cards.h"

namespace voxremesh::assembly {

/// Collects the references found in one block.
struct ReferenceSink {
  std::size_t block;
  const std::unordered_set<Id>& watched;
  std::vector<NodeReference>& references;

  /// Appends a reference (offset, length, width as in NodeReference).
  void add(std::size_t offset, std::size_t length, std::size_t width, std::size_t line, Id node,
           ReferenceKind kind, std::string_view keyword, std::string reason = {}) const;
  /// Appends a Range reference for every watched node in first, first + step, ..., last.
  void addRange(std::size_t line, Id first, Id last, Id step, std::string_view keyword) const;
  /// Appends a Suspect reference for every integer token of `line` (blank- or comma-separated)
  /// that is a watched node, leaving out the first `skipTokens` tokens.
  void scanSuspects(std::string_view line, std::size_t lineInBlock, std::size_t skipTokens,
                    std::string_view keyword) const;
};

/// The card format of the keywords of an LS-DYNA deck without a suffix (from its *KEYWORD line).
io::lsdyna::CardFormat lsDynaDeckFormat(const FeModel& model);

/// Scans one LS-DYNA keyword block.
void scanLsDynaBlock(std::string_view text, io::lsdyna::CardFormat deckFormat,
                     const ReferenceSink& sink);
/// Scans one LS-DYNA keyword block for references to watched shells: shell sets (*SET_SHELL...,
/// members; GENERATE ranges), history lists (*DATABASE_HISTORY_SHELL, members), and
/// *LOAD_SHELL_ELEMENT and *DATABASE_HISTORY_SHELL_ID (records).
void scanLsDynaElementBlock(std::string_view text, io::lsdyna::CardFormat deckFormat,
                            const ReferenceSink& sink);
/// Scans one run of Nastran bulk data lines.
void scanNastranBlock(std::string_view text, const ReferenceSink& sink);
/// Appends the PLOAD4 cards of one run of Nastran bulk data lines (block `block`) to `out`.
void scanNastranPressures(std::string_view text, std::size_t block,
                          std::vector<ElementPressure>& out);
/// Scans one run of Nastran bulk data lines for loads on watched elements (PLOAD4).
void scanNastranLoads(std::string_view text, const ReferenceSink& sink);
/// Scans one run of Abaqus input lines.
void scanAbaqusBlock(std::string_view text, const ReferenceSink& sink);
/// Scans one run of Abaqus input lines for references to watched shells: *ELSET lists
/// (members; GENERATE ranges) and *DLOAD lines naming an element (records).
void scanAbaqusElementBlock(std::string_view text, const ReferenceSink& sink);

/// Largest element ID of the element keywords in one block of each format (0 when none).
Id lsDynaMaxElementId(std::string_view text);
Id nastranMaxElementId(std::string_view text);
Id abaqusMaxElementId(std::string_view text);

}  // namespace voxremesh::assembly
