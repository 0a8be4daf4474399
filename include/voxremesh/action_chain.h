// Action chains in the style of OpenVDB's vdb_tool:
//   voxremesh -read part.k -voxelize size=2 -write part.vdb -print -slice axis=z at=0 file=z.png
// runs actions left to right on a stack of items (decks, quad meshes, volumes).
//
// Syntax
// - An action is a word after '-' ("-read"); a unique prefix is enough ("-vox"), an exact name
//   always wins, an ambiguous prefix is an error listing the candidates.
// - Its options follow as key=value ("size=2"); keys match by unique prefix too. An action may
//   name one positional option that takes a bare value ("-read part.k" is "-read file=part.k").
// - Values are checked against the option's type (number, whole number, text, 0/1 flag) when the
//   chain is parsed, so a bad value fails before any action runs.
// - "-config FILE" inserts the actions of a config file at its place: one action per line, the
//   leading '-' optional, '#' starts a comment, double quotes keep blanks in a value
//   (file="my part.k"). "-save-chain FILE" writes the whole chain (without -save-chain) as such a
//   file, so replaying it with -config runs the same actions with the same options.
// - "-help" lists the actions, "-help ACTION" (or -help action=ACTION) describes one; a chain
//   that contains -help only prints help.
// Stack
// - read pushes a deck (any deck or mesh format) or a volume (.vdb).
// - A volume item holds one volume per sheet of its part (volume.h buildSheetVolumes): voxelize
//   makes them, write stores them all in one .vdb (writeVolumes), extract extracts each and joins
//   them at their junction nodes (pipeline.h extractPartMesh), print reports each, slice draws
//   one (sheet=).
// - Actions that need an item use the topmost item of the kind they need (voxelize: a deck;
//   slice: a volume; extract: a volume; optimize: a quad mesh; quality: a quad mesh or deck;
//   write and print: the top item) and push what they make on top.
// - voxelize remembers the shells of the part it voxelized, extract and optimize pass them on:
//   they are the original surface optimize projects on and quality measures the distance to (a
//   volume read from a .vdb file has none; optimize then takes the part from the topmost deck
//   that has it, or from original=FILE).
// - write of a quad mesh assembles it into the topmost deck that has its part (deck_assembly.h)
//   when there is one, else writes the mesh alone.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/quality.h"
#include "voxremesh/volume.h"

namespace voxremesh::chain {

/// The type of an option's value.
enum class OptionType { Number, Integer, Text, Flag };

/// An option an action accepts.
struct OptionDef {
  std::string name;
  OptionType type = OptionType::Text;
  std::string defaultValue;  ///< empty: no default (the option is optional or required)
  std::string help;
  bool required = false;
};

struct ActionCall;
struct ChainState;

/// Runs one action on the state. Throws on failure (InputError, SettingError,
/// std::runtime_error, ...).
using ActionFunction = void (*)(ChainState& state, const ActionCall& call);

/// An action of the chain.
struct ActionDef {
  std::string name;
  std::string summary;
  std::string positional;  ///< the option a bare value sets ("" for none)
  std::vector<OptionDef> options;
  ActionFunction run = nullptr;
  std::string help;  ///< more text for -help ACTION
};

/// One parsed action with its option values (defaults filled in).
struct ActionCall {
  const ActionDef* action = nullptr;
  std::map<std::string, std::string> values;  ///< given and default values, by full option name
  std::map<std::string, bool> given;          ///< which options the user gave
  std::string origin;                         ///< "argument 3" or "chain.cfg:4", for messages

  /// The option was given by the user.
  bool has(const std::string& option) const;
  /// The value of an option (given or default); "" when it has none.
  const std::string& text(const std::string& option) const;
  /// The value as a number / whole number / flag (validated when parsing).
  double number(const std::string& option) const;
  long long integer(const std::string& option) const;
  bool flag(const std::string& option) const;
};

/// A parsed chain.
using Chain = std::vector<ActionCall>;

/// All actions, in the order -help lists them.
const std::vector<ActionDef>& actions();

/// The action whose name is `word` or starts with it (an exact name wins).
/// Throws SettingError naming the word and listing the candidates (ambiguous) or all actions
/// (unknown).
const ActionDef& findAction(const std::string& word);

/// Parses a chain from command line arguments (argv after the program name). -config FILE is
/// replaced by the file's actions.
/// Throws SettingError naming the argument for an unknown or ambiguous action or option, a value
/// of the wrong type, a missing required option, or text before the first action; InputError
/// naming the file and line for errors in a config file (or one that cannot be read).
Chain parseChain(const std::vector<std::string>& args);

/// Parses a config file (see the syntax above). Throws InputError naming the file and line.
Chain parseConfig(const std::filesystem::path& path);

/// The chain as config file text (one action per line, every given option as key=value), such
/// that parseConfig of it gives the same actions and values. -save-chain actions are left out.
std::string formatChain(const Chain& chain);

/// The help text: all actions with their summaries, or one action with its options.
/// Throws SettingError as findAction for an unknown action.
std::string chainHelp(const std::string& action = {});

/// An item on the stack.
struct ChainItem {
  enum class Kind { Deck, Mesh, Volume };
  Kind kind = Kind::Deck;
  std::string name;  ///< where it came from ("part.k", "voxelize part 4075")
  FeModel deck;
  QuadMesh mesh;
  /// Volumes: one per sheet of the part (buildSheetVolumes, readVolumes), sheet order; a .vdb
  /// file of one volume gives one.
  std::vector<Volume> volumes;
  /// Volumes made by voxelize and the meshes made from them: the shells of the part they were
  /// made from (the original surface); empty when unknown (a volume read from a .vdb file).
  QuadMesh original;
  /// Volumes and meshes: the target element size they were made for (the voxel size); 0 for
  /// decks.
  double targetSize = 0.0;
};

/// What the actions work on and report to.
struct ChainState {
  std::vector<ChainItem> stack;
  /// Receives what actions print (summaries, reports); defaults to nothing.
  std::function<void(const std::string&)> print;
  /// Receives warnings about the input as they occur.
  std::function<void(const std::string&)> warn;
  Chain chain;  ///< the chain being run (for -save-chain)
  /// The report of the last -quality action (batch summaries read it); empty without one.
  std::optional<QualityReport> quality;
};

/// Runs the actions in order. A chain with a -help action prints the help instead.
/// Throws the first action's error with the action and its origin prepended to the message
/// (InputError keeps its file and line).
void runChain(const Chain& chain, ChainState& state);

}  // namespace voxremesh::chain
