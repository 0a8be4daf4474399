// Reading Nastran bulk data (.bdf .nas .dat) into an FeModel.
//
// GRID and the shells we can hold (CQUAD4, CTRIA3, CQUADR, CTRIAR) become geometry; everything
// else (executive and case control, other cards with their continuations, comments, ENDDATA and
// what follows) is kept verbatim, byte for byte, in file order. INCLUDEs in the bulk data are read
// in place. Shell property cards (PSHELL, PCOMP, PCOMPG, PCOMPP) stay verbatim and define the
// parts; part names come from HyperMesh ($HMNAME PROP) and ANSA ($ANSA_NAME_COMMENT, $ANSA_NAME)
// comments.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/formats.h"
#include "io/model_checks.h"
#include "io/nastran_cards.h"
#include "io/nastran_coords.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

namespace fs = std::filesystem;
using nastran::CardFields;

/// What a card is to the reader.
enum class CardKind {
  Other,        ///< kept verbatim
  Grid,         ///< GRID
  Shell,        ///< CQUAD4, CTRIA3, CQUADR, CTRIAR
  Property,     ///< PSHELL, PCOMP, PCOMPG, PCOMPP: verbatim, and a part
  GridSet,      ///< GRDSET: verbatim; its CP applies to GRIDs with CP blank
  CoordSystem,  ///< CORD2R, CORD2C, CORD2S: verbatim, and read for GRIDs given in them (CP)
  Include,      ///< INCLUDE 'file'
  EndData,      ///< ENDDATA
  Begin,        ///< BEGIN SUPER=... (partitioned bulk data)
  Unsupported   ///< shells we cannot represent (CQUAD8, CTRIA6, CQUAD)
};

/// A shell card: its name, node count and whether it is of the CQUADR/CTRIAR family.
struct ShellCard {
  const char* name;
  std::uint8_t nodeCount;
  bool rFamily;
};

constexpr ShellCard kShellCards[] = {
    {"CQUAD4", 4, false}, {"CTRIA3", 3, false}, {"CQUADR", 4, true}, {"CTRIAR", 3, true}};

CardKind classify(std::string_view name, const ShellCard*& shell) {
  shell = nullptr;
  if (name.empty()) return CardKind::Other;
  switch (name[0]) {
    case 'G':
    case 'g':
      if (iequals(name, "GRID")) return CardKind::Grid;
      if (iequals(name, "GRDSET")) return CardKind::GridSet;
      break;
    case 'C':
    case 'c':
      for (const ShellCard& card : kShellCards)
        if (iequals(name, card.name)) {
          shell = &card;
          return CardKind::Shell;
        }
      if (iequals(name, "CQUAD8") || iequals(name, "CTRIA6") || iequals(name, "CQUAD"))
        return CardKind::Unsupported;
      if (iequals(name, "CORD2R") || iequals(name, "CORD2C") || iequals(name, "CORD2S"))
        return CardKind::CoordSystem;
      break;
    case 'P':
    case 'p':
      if (iequals(name, "PSHELL") || iequals(name, "PCOMP") || iequals(name, "PCOMPG") ||
          iequals(name, "PCOMPP"))
        return CardKind::Property;
      break;
    case 'I':
    case 'i':
      if (iequals(name, "INCLUDE")) return CardKind::Include;
      break;
    case 'E':
    case 'e':
      if (iequals(name, "ENDDATA")) return CardKind::EndData;
      break;
    case 'B':
    case 'b':
      if (iequals(name, "BEGIN")) return CardKind::Begin;
      break;
    default:
      break;
  }
  return CardKind::Other;
}

/// True for the line that ends executive and case control: BEGIN BULK (any case and spacing).
bool isBeginBulk(std::string_view line) {
  line = trim(line);
  if (!istartsWith(line, "BEGIN") || line.size() < 6 || (line[5] != ' ' && line[5] != '\t'))
    return false;
  return istartsWith(trim(line.substr(5)), "BULK");
}

/// True for a line that can only be bulk data (a GRID or shell card), ending the search for
/// BEGIN BULK.
bool isGeometryLine(std::string_view line) {
  if (line.empty() || line[0] == '$' || line[0] == ' ' || line[0] == '\t') return false;
  const nastran::CardName name = nastran::cardName(line);
  if (name.name.size() == line.size()) return false;  // a bare word: no fields
  const ShellCard* shell = nullptr;
  const CardKind kind = classify(name.name, shell);
  return kind == CardKind::Grid || kind == CardKind::Shell;
}

/// Returns the text after the first '"' up to the last '"' of a comment, or false.
bool quotedName(std::string_view text, std::string_view& name) {
  const std::size_t first = text.find('"');
  const std::size_t last = text.rfind('"');
  if (first == std::string_view::npos || last == first) return false;
  name = text.substr(first + 1, last - first - 1);
  return true;
}

/// Splits `text` at `separator` into at most `max` pieces; returns the count.
std::size_t splitAt(std::string_view text, char separator, std::string_view* pieces,
                    std::size_t max) {
  std::size_t count = 0;
  while (count < max) {
    const std::size_t at = text.find(separator);
    pieces[count++] = text.substr(0, at);
    if (at == std::string_view::npos) break;
    text.remove_prefix(at + 1);
  }
  return count;
}

/// The parts' names found in preprocessor comments, by property ID.
class NameComments {
 public:
  /// Looks at one comment line (and the line before it, for ANSA's two-line form).
  void scan(std::string_view line) {
    const bool legacyPending = legacyPending_;
    legacyPending_ = false;
    if (line.size() < 2 || line[0] != '$') return;
    if (legacyPending) {
      // $ANSA_NAME;<id>;PSHELL;~ is followed by $<name>
      names_.emplace(legacyId_, std::string(trim(line.substr(1))));
      return;
    }
    if (istartsWith(line, "$HMNAME PROP")) {
      std::string_view rest = line.substr(12);
      const std::size_t quote = rest.find('"');
      std::int64_t id = 0;
      std::string_view name;
      if (quote != std::string_view::npos && parseInt(rest.substr(0, quote), id) &&
          quotedName(rest, name))
        names_.emplace(id, std::string(name));
    } else if (istartsWith(line, "$ANSA_NAME_COMMENT;")) {
      std::string_view pieces[5];
      std::int64_t id = 0;
      if (splitAt(line, ';', pieces, 5) >= 4 && parseInt(pieces[1], id))
        names_.emplace(id, std::string(trim(pieces[3])));
    } else if (istartsWith(line, "$ANSA_NAME;")) {
      std::string_view pieces[4];
      std::int64_t id = 0;
      if (splitAt(line, ';', pieces, 4) >= 3 && parseInt(pieces[1], id)) {
        legacyPending_ = true;
        legacyId_ = id;
      }
    }
  }

  /// Forgets a pending two-line ANSA name (a non-comment line came between).
  void interrupt() { legacyPending_ = false; }

  /// The name found for a property ID, or nullptr.
  const std::string* find(Id id) const {
    const auto it = names_.find(id);
    return it == names_.end() ? nullptr : &it->second;
  }

 private:
  std::unordered_map<Id, std::string> names_;
  bool legacyPending_ = false;
  Id legacyId_ = 0;
};

/// Builds FeModel::blocks: verbatim runs between the places of the nodes and the shells.
class BlockBuilder {
 public:
  explicit BlockBuilder(std::vector<DeckBlock>& blocks) : blocks_(blocks) {}

  void verbatim(std::string_view raw) {
    if (blocks_.empty() || blocks_.back().kind != DeckBlock::Kind::Verbatim) {
      newVerbatim(raw);
      return;
    }
    terminateLastLine(raw);
    blocks_.back().text.append(raw);
  }
  /// Starts a new verbatim block (ENDDATA gets its own so the writer finds it).
  void newVerbatim(std::string_view raw) {
    terminateLastLine(raw);
    blocks_.push_back(DeckBlock{DeckBlock::Kind::Verbatim, std::string(raw)});
  }
  void nodesHere() {
    if (nodesPlaced_) return;
    nodesPlaced_ = true;
    terminateLastLine("\n");
    blocks_.push_back(DeckBlock{DeckBlock::Kind::Nodes, {}});
  }
  void shellsHere() {
    if (shellsPlaced_) return;
    shellsPlaced_ = true;
    terminateLastLine("\n");
    blocks_.push_back(DeckBlock{DeckBlock::Kind::Shells, {}});
  }

 private:
  /// The last line of an included file may lack its terminator: before anything follows it, end
  /// it (with CR LF when the line that follows has one) so that two lines are never glued.
  void terminateLastLine(std::string_view next) {
    for (auto it = blocks_.rbegin(); it != blocks_.rend(); ++it) {
      if (it->kind != DeckBlock::Kind::Verbatim || it->text.empty()) continue;
      if (it->text.back() != '\n') {
        const bool crlf = next.size() >= 2 && next[next.size() - 2] == '\r';
        it->text.append(crlf ? "\r\n" : "\n");
      }
      return;
    }
  }

  std::vector<DeckBlock>& blocks_;
  bool nodesPlaced_ = false;
  bool shellsPlaced_ = false;
};

/// One file being read: its name for messages and its index in the SourceMap.
struct FileContext {
  std::string name;
  std::uint32_t index = 0;
  fs::path folder;
};

class Reader {
 public:
  explicit Reader(Warnings& warnings) : warnings_(warnings), blocks_(model_.blocks) {}

  FeModel read(const fs::path& path) {
    model_.sourceFormat = DeckFormat::Nastran;
    const std::string content = loadFile(path);
    requireText(content, path);
    model_.nodes.reserve(content.size() / 120);
    model_.shells.reserve(content.size() / 120);
    FileContext file{path.string(), sources_.addFile(path.string()), path.parent_path()};
    includeStack_.push_back(canonical(path));

    LineCursor cursor(content);
    const std::size_t headerLines = findBeginBulk(content);
    if (headerLines > 0) {
      std::size_t headerEnd = 0;
      while (cursor.lineNumber() < headerLines && cursor.next()) {
        headerEnd = cursor.end();
        if (istartsWith(trim(cursor.line()), "INCLUDE"))
          warnings_.push_back(file.name + ":" + std::to_string(cursor.lineNumber()) +
                              ": INCLUDE before BEGIN BULK is kept as written, not read");
      }
      blocks_.verbatim(std::string_view(content).substr(0, headerEnd));
    }
    readBulk(cursor, file);
    finish();
    return std::move(model_);
  }

 private:
  /// Number of the BEGIN BULK line, or 0 when the file is bulk data throughout.
  static std::size_t findBeginBulk(std::string_view content) {
    LineCursor cursor(content);
    while (cursor.next()) {
      const std::string_view line = cursor.line();
      if (isBeginBulk(line)) return cursor.lineNumber();
      if (isGeometryLine(line)) return 0;
    }
    return 0;
  }

  static fs::path canonical(const fs::path& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(path, error);
    return error ? path : result;
  }

  void readBulk(LineCursor& cursor, const FileContext& file) {
    while (cursor.next()) {
      const std::string_view line = cursor.line();
      if (afterEnd_) {
        if (!line.empty() && line[0] == '$') names_.scan(line);
        blocks_.verbatim(cursor.rawLine());
        continue;
      }
      if (nastran::isCommentOrBlank(line)) {
        names_.scan(line);
        blocks_.verbatim(cursor.rawLine());
        continue;
      }
      names_.interrupt();
      if (nastran::isContinuationLine(line)) {
        if (open_ != CardKind::Other) {
          card_.addContinuation(cursor.lineNumber(), line);
          if (open_ == CardKind::CoordSystem) blocks_.verbatim(cursor.rawLine());
        } else {
          blocks_.verbatim(cursor.rawLine());
        }
        continue;
      }
      finishCard(file);
      startCard(cursor, file);
    }
    finishCard(file);
  }

  void startCard(LineCursor& cursor, const FileContext& file) {
    const std::string_view line = cursor.line();
    const nastran::CardName name = nastran::cardName(line);
    const ShellCard* shell = nullptr;
    const CardKind kind = classify(name.name, shell);
    switch (kind) {
      case CardKind::Grid:
      case CardKind::Shell:
        if (partitioned_)
          throw InputError(file.name, cursor.lineNumber(),
                           "GRID and shell cards after BEGIN SUPER (partitioned bulk data) are not "
                           "supported: they would move out of their superelement",
                           std::string(line));
        if (kind == CardKind::Grid) {
          blocks_.nodesHere();
        } else {
          blocks_.shellsHere();
        }
        open_ = kind;
        openShell_ = shell;
        card_.start(&file.name, cursor.lineNumber(), line);
        return;
      case CardKind::CoordSystem:
        open_ = kind;
        coordType_ = char(std::toupper(static_cast<unsigned char>(name.name[5])));
        card_.start(&file.name, cursor.lineNumber(), line);
        break;
      case CardKind::Property:
        addProperty(cursor, file, name.name);
        break;
      case CardKind::GridSet:
        readGridSet(cursor, file);
        break;
      case CardKind::Include:
        include(cursor, file);
        return;
      case CardKind::EndData:
        afterEnd_ = true;
        blocks_.newVerbatim(cursor.rawLine());
        return;
      case CardKind::Begin: {
        // BEGIN SUPER=n, BEGIN BULK AUXMODEL=n, ...: bulk data of another part follows. A plain
        // repeated BEGIN BULK (some include files start with one) changes nothing.
        std::string_view rest = line;
        const std::size_t dollar = rest.find('$');
        if (dollar != std::string_view::npos) rest = rest.substr(0, dollar);
        rest = trim(rest);
        if (!(isBeginBulk(rest) && iequals(rest.substr(rest.size() - 4), "BULK")))
          partitioned_ = true;
        break;
      }
      case CardKind::Unsupported:
        throw InputError(file.name, cursor.lineNumber(),
                         std::string(name.name) +
                             " elements (shells with midside nodes or CQUAD) cannot be read: "
                             "convert them to CQUAD4/CTRIA3 first",
                         std::string(line));
      case CardKind::Other:
        break;
    }
    blocks_.verbatim(cursor.rawLine());
  }

  void finishCard(const FileContext& file) {
    if (open_ == CardKind::Grid) {
      readGrid(file);
    } else if (open_ == CardKind::Shell) {
      readShell(file);
    } else if (open_ == CardKind::CoordSystem) {
      readCoordSystem(file);
    }
    open_ = CardKind::Other;
  }

  // ---- cards ----------------------------------------------------------------------------------

  [[noreturn]] void fieldError(const FileContext& file, std::size_t k,
                               const std::string& message) const {
    throw InputError(file.name, card_.lineOf(k), message, std::string(card_.lineTextOf(k)));
  }

  /// The card being read as messages name it: "GRID 12", "CQUAD4 7" (the type alone before its
  /// ID is known). Built only when a message needs it.
  std::string label() const {
    return cardIdKnown_ ? std::string(cardType_) + " " + std::to_string(cardId_)
                        : std::string(cardType_);
  }

  void setLabel(const char* type) {
    cardType_ = type;
    cardIdKnown_ = false;
  }

  void setLabelId(Id id) {
    cardId_ = id;
    cardIdKnown_ = true;
  }

  std::int64_t intField(const FileContext& file, std::size_t k, const char* what, bool required,
                        std::int64_t fallback = 0) const {
    const std::string_view text = card_[k];
    if (text.empty() && required)
      fieldError(file, k, std::string("missing ") + what + " in " + label());
    std::int64_t value = 0;
    if (!parseInt(text, value, fallback))
      fieldError(file, k,
                 std::string("malformed ") + what + " '" + std::string(text) + "' in " + label());
    return value;
  }

  double realField(const FileContext& file, std::size_t k, const char* what) const {
    const std::string_view text = card_[k];
    double value = 0.0;
    if (!parseReal(text, value, 0.0))
      fieldError(file, k,
                 std::string("malformed ") + what + " '" + std::string(text) + "' in " + label());
    return value;
  }

  /// An integer field that must fit 32 bits (coordinate system, component and superelement IDs).
  std::int32_t smallInt(const FileContext& file, std::size_t k, const char* what) const {
    const std::int64_t value = intField(file, k, what, false);
    if (value < INT32_MIN || value > INT32_MAX)
      fieldError(
          file, k,
          std::string(what) + " " + std::to_string(value) + " in " + label() + " is out of range");
    return static_cast<std::int32_t>(value);
  }

  /// Refuses non-blank data in fields [from, to) (to = the card's end by default).
  void requireBlank(const FileContext& file, std::size_t from, const char* layout,
                    std::size_t to = std::numeric_limits<std::size_t>::max()) const {
    for (std::size_t k = from; k < std::min(to, card_.size()); ++k)
      if (!card_[k].empty())
        fieldError(file, k,
                   "unexpected data '" + std::string(card_[k]) + "' in " + label() +
                       " (its fields are " + layout + ")");
  }

  /// A card whose last line announces a continuation that never came (a truncated card).
  void requireNoPendingContinuation(const FileContext& file, const char* missing) const {
    if (card_.endsInHalfLine() && !card_.pendingMarker().empty())
      throw InputError(file.name, card_.firstLine(),
                       "truncated " + label() + ": its continuation line '" +
                           std::string(card_.pendingMarker()) + "' (" + missing + ") is missing",
                       std::string(card_.firstText()));
  }

  void readGrid(const FileContext& file) {
    setLabel("GRID");
    if (card_[0].empty()) fieldError(file, 0, "GRID without an ID");
    const Id id = intField(file, 0, "grid ID", true);
    setLabelId(id);
    requireNoPendingContinuation(file, "X3, CD, PS, SEID");
    const std::int64_t cp = intField(file, 1, "CP (coordinate system)", false);
    if (cp < 0) fieldError(file, 1, "negative CP in " + label());
    if (cp != 0)
      localGrids_.push_back({model_.nodes.size(), Id(cp), file.name, card_.lineOf(1),
                             std::string(card_.lineTextOf(1))});
    if (card_[1].empty() && !blankCpGrid_) {
      blankCpGrid_ = true;
      blankCpFile_ = file.name;
      blankCpLine_ = card_.firstLine();
    }
    Node node;
    node.id = id;
    node.xyz[0] = realField(file, 2, "X1 coordinate");
    node.xyz[1] = realField(file, 3, "X2 coordinate");
    node.xyz[2] = realField(file, 4, "X3 coordinate");
    NodeExtras extras;
    extras.nastranCd = smallInt(file, 5, "CD (displacement system)");
    extras.nastranPs = smallInt(file, 6, "PS (permanent constraints)");
    extras.nastranSeid = smallInt(file, 7, "SEID (superelement)");
    requireBlank(file, 8, "ID CP X1 X2 X3 CD PS SEID");
    if (extras.nastranCd != 0 || extras.nastranPs != 0 || extras.nastranSeid != 0)
      model_.nodeExtras[id] = extras;
    model_.nodes.push_back(node);
    sources_.addNode(file.index, card_.firstLine());
  }

  /// CORD2R/CORD2C/CORD2S CID RID A1 A2 A3 B1 B2 B3 C1 C2 C3 (kept verbatim as well).
  void readCoordSystem(const FileContext& file) {
    setLabel(coordType_ == 'C' ? "CORD2C" : coordType_ == 'S' ? "CORD2S" : "CORD2R");
    const Id id = intField(file, 0, "coordinate system ID (CID)", true);
    setLabelId(id);
    if (id <= 0) fieldError(file, 0, label() + ": its ID must be positive");
    requireNoPendingContinuation(file, "C1, C2, C3");
    nastran::CoordCard card;
    card.type = coordType_;
    card.rid = intField(file, 1, "reference system (RID)", false);
    if (card.rid < 0) fieldError(file, 1, label() + ": negative RID");
    static const char* const kPoints[] = {"A1", "A2", "A3", "B1", "B2", "B3", "C1", "C2", "C3"};
    for (std::size_t k = 0; k < 9; ++k) {
      std::array<double, 3>& point = k < 3 ? card.a : k < 6 ? card.b : card.c;
      point[k % 3] = realField(file, 2 + k, kPoints[k]);
    }
    requireBlank(file, 11, "CID RID A1 A2 A3 B1 B2 B3 C1 C2 C3");
    card.file = file.name;
    card.line = card_.firstLine();
    card.text = std::string(card_.firstText());
    const auto [it, inserted] = coordCards_.emplace(id, card);
    if (!inserted)
      fieldError(file, 0,
                 "duplicate coordinate system ID " + std::to_string(id) + " (first defined at " +
                     it->second.file + ":" + std::to_string(it->second.line) + ")");
  }

  /// Moves the GRIDs given in local systems into the basic system.
  void transformLocalGrids() {
    if (localGrids_.empty()) return;
    const std::map<Id, nastran::CoordFrame> frames = nastran::resolveCoordFrames(coordCards_);
    for (const LocalGrid& grid : localGrids_) {
      const auto frame = frames.find(grid.cp);
      if (frame == frames.end())
        throw InputError(grid.file, grid.line,
                         "GRID " + std::to_string(model_.nodes[grid.node].id) +
                             " is given in coordinate system CP = " + std::to_string(grid.cp) +
                             ", which the deck does not define by a CORD2R, CORD2C or CORD2S "
                             "card",
                         grid.text);
      Node& node = model_.nodes[grid.node];
      node.xyz = nastran::toBasic(frame->second, node.xyz);
    }
  }

  void readShell(const FileContext& file) {
    const ShellCard& spec = *openShell_;
    setLabel(spec.name);
    const Id id = intField(file, 0, "element ID", true);
    setLabelId(id);
    requireNoPendingContinuation(file, "TFLAG, T1..T4");
    Shell shell;
    shell.id = id;
    shell.part = intField(file, 1, "property ID (PID)", false, id);
    shell.nodeCount = spec.nodeCount;
    static const char* const kGridNames[] = {"G1", "G2", "G3", "G4"};
    for (std::size_t i = 0; i < spec.nodeCount; ++i)
      shell.nodes[i] = intField(file, 2 + i, kGridNames[i], true);
    const std::size_t thetaField = 2 + spec.nodeCount;  // THETA/MCID, then ZOFFS
    ShellExtras extras;
    const std::string_view theta = card_[thetaField];
    std::int64_t mcid = 0;
    if (!theta.empty() && parseInt(theta, mcid)) {
      extras.angleIsMcid = true;
      extras.angle = static_cast<double>(mcid);
    } else {
      extras.angle = realField(file, thetaField, "THETA (material angle)");
    }
    extras.offset = realField(file, thetaField + 1, "ZOFFS (offset)");
    const char* layout = spec.nodeCount == 4
                             ? "EID PID G1 G2 G3 G4 THETA/MCID ZOFFS, then blank TFLAG T1 T2 T3 T4"
                             : "EID PID G1 G2 G3 THETA/MCID ZOFFS blank, then blank TFLAG T1 T2 T3";
    requireBlank(file, thetaField + 2, layout, 9);
    const std::int64_t tflag = intField(file, 9, "TFLAG", false);
    if (tflag != 0)
      fieldError(file, 9,
                 label() + " gives TFLAG = " + std::to_string(tflag) +
                     " (thicknesses relative to the property), which voxremesh cannot hold: "
                     "give T1..T4 as absolute thicknesses (TFLAG blank or 0)");
    static const char* const kThicknessNames[] = {"T1 thickness", "T2 thickness", "T3 thickness",
                                                  "T4 thickness"};
    for (std::size_t i = 0; i < spec.nodeCount; ++i)
      extras.thickness[i] = realField(file, 10 + i, kThicknessNames[i]);
    requireBlank(file, 10 + spec.nodeCount, layout);

    const bool hasExtras = extras.angle != 0.0 || extras.angleIsMcid || extras.offset != 0.0 ||
                           extras.thickness[0] != 0.0 || extras.thickness[1] != 0.0 ||
                           extras.thickness[2] != 0.0 || extras.thickness[3] != 0.0;
    if (hasExtras) {
      shell.extras = static_cast<std::int32_t>(model_.shellExtras.size());
      model_.shellExtras.push_back(extras);
    }
    if (spec.rFamily) {
      if (spec.nodeCount == 4) {
        if (quadRType_ == 0) quadRType_ = model_.internShellType("CQUADR");
        shell.type = quadRType_;
      } else {
        if (triaRType_ == 0) triaRType_ = model_.internShellType("CTRIAR");
        shell.type = triaRType_;
      }
    }
    model_.shells.push_back(shell);
    sources_.addShell(file.index, card_.firstLine());
  }

  void addProperty(LineCursor& cursor, const FileContext& file, std::string_view cardType) {
    nastran::LineFields fields;
    nastran::splitLine(cursor.line(), false, fields, scratch_);
    std::int64_t id = 0;
    if (fields.data[0].empty() || !parseInt(fields.data[0], id))
      throw InputError(
          file.name, cursor.lineNumber(),
          "malformed property ID '" + std::string(fields.data[0]) + "' in " + toUpper(cardType),
          std::string(cursor.line()));
    const std::string location = file.name + ":" + std::to_string(cursor.lineNumber());
    const auto [it, inserted] = propertyAt_.emplace(id, location);
    if (!inserted)
      throw InputError(
          file.name, cursor.lineNumber(),
          "duplicate property ID " + std::to_string(id) + " (first defined at " + it->second + ")",
          std::string(cursor.line()));
    Part& part = model_.partOrAdd(id);
    part.definedInBlocks = true;
  }

  void readGridSet(LineCursor& cursor, const FileContext& file) {
    nastran::LineFields fields;
    nastran::splitLine(cursor.line(), false, fields, scratch_);
    std::int64_t cp = 0;
    if (!parseInt(fields.data[1], cp))
      throw InputError(file.name, cursor.lineNumber(),
                       "malformed CP '" + std::string(fields.data[1]) + "' in GRDSET",
                       std::string(cursor.line()));
    if (cp != 0) {
      gridSetCp_ = cp;
      gridSetFile_ = file.name;
      gridSetLine_ = cursor.lineNumber();
      gridSetText_ = std::string(cursor.line());
    }
  }

  // ---- INCLUDE --------------------------------------------------------------------------------

  void include(LineCursor& cursor, const FileContext& file) {
    const std::size_t line = cursor.lineNumber();
    const std::string statement(cursor.line());
    std::string_view rest = cursor.line().substr(7);
    const std::size_t dollar = rest.find('$');
    std::string name;
    const std::size_t open = rest.find_first_of("'\"");
    if (open == std::string_view::npos || (dollar != std::string_view::npos && dollar < open)) {
      if (dollar != std::string_view::npos) rest = rest.substr(0, dollar);
      name = std::string(trim(rest));
      if (name.empty()) throw InputError(file.name, line, "INCLUDE without a file name", statement);
    } else {
      const char quote = rest[open];
      std::string_view piece = rest.substr(open + 1);
      while (true) {
        const std::size_t close = piece.find(quote);
        name += std::string(trim(piece.substr(0, close)));
        if (close != std::string_view::npos) break;
        if (!cursor.next())
          throw InputError(file.name, line, "INCLUDE file name without its closing quote",
                           statement);
        piece = cursor.line();
      }
    }
    const auto isFile = [](const fs::path& candidate) {
      std::error_code error;
      return fs::is_regular_file(candidate, error);
    };
    fs::path target = fs::path(name);
    if (target.is_relative()) target = file.folder / target;
    if (!isFile(target) && name.find('\\') != std::string::npos) {
      std::string slashes = name;
      std::replace(slashes.begin(), slashes.end(), '\\', '/');
      fs::path alternative = fs::path(slashes);
      if (alternative.is_relative()) alternative = file.folder / alternative;
      if (isFile(alternative)) target = alternative;
    }
    if (!isFile(target))
      throw InputError(file.name, line,
                       "INCLUDE file '" + name + "' not found as a regular file (looked for " +
                           target.string() + ")",
                       statement);
    const fs::path key = canonical(target);
    if (std::find(includeStack_.begin(), includeStack_.end(), key) != includeStack_.end())
      throw InputError(file.name, line,
                       "INCLUDE of '" + name + "' makes a cycle (the file includes itself)",
                       statement);
    if (includeStack_.size() >= io::kMaxIncludeDepth)
      throw InputError(file.name, line, io::includeTooDeepMessage(name), statement);
    warnings_.push_back(file.name + ":" + std::to_string(line) + ": INCLUDE '" + name +
                        "' was read in place; its content is written inline, not as an INCLUDE");

    const std::string content = loadFile(target);
    const bool blank = trim(content).find_first_not_of(" \t\r\n") == std::string_view::npos;
    if (!blank || content.find('\0') != std::string::npos) requireText(content, target);
    if (blank) {
      warnings_.push_back(target.string() + ": included file is empty");
      return;
    }
    FileContext child{target.string(), sources_.addFile(target.string()), target.parent_path()};
    includeStack_.push_back(key);
    LineCursor childCursor(content);
    readBulk(childCursor, child);
    includeStack_.pop_back();
  }

  // ---- end ------------------------------------------------------------------------------------

  void finish() {
    if (gridSetCp_ != 0 && blankCpGrid_)
      throw InputError(gridSetFile_, gridSetLine_,
                       "GRDSET sets the default CP = " + std::to_string(gridSetCp_) +
                           " for GRIDs with CP blank (first at " + blankCpFile_ + ":" +
                           std::to_string(blankCpLine_) +
                           "), a local coordinate system voxremesh cannot transform: export the "
                           "deck with GRID coordinates in the basic system",
                       gridSetText_);
    transformLocalGrids();
    // Parts the elements use without a property card.
    const std::vector<Id> missing = addUndefinedParts(model_);
    if (!missing.empty())
      warnings_.push_back(std::string("elements use ") +
                          (missing.size() == 1 ? "property " : "properties ") + listIds(missing) +
                          ", which the deck does not define (no PSHELL or PCOMP); a PSHELL is "
                          "generated for each when the model is written as Nastran");
    for (Part& part : model_.parts)
      if (const std::string* name = names_.find(part.id)) part.name = *name;
    checkModel(model_, sources_);
  }

  Warnings& warnings_;
  FeModel model_;
  SourceMap sources_;
  BlockBuilder blocks_;
  NameComments names_;
  CardFields card_;
  CardKind open_ = CardKind::Other;
  const ShellCard* openShell_ = nullptr;
  const char* cardType_ = "";
  Id cardId_ = 0;
  bool cardIdKnown_ = false;
  std::string scratch_;
  std::unordered_map<Id, std::string> propertyAt_;
  std::vector<fs::path> includeStack_;
  std::uint8_t quadRType_ = 0;
  std::uint8_t triaRType_ = 0;
  bool afterEnd_ = false;
  bool partitioned_ = false;
  bool blankCpGrid_ = false;
  std::string blankCpFile_;
  std::size_t blankCpLine_ = 0;
  std::int64_t gridSetCp_ = 0;
  /// A GRID given in a local system, transformed once all systems are read.
  struct LocalGrid {
    std::size_t node;  ///< index into model_.nodes
    Id cp;
    std::string file;
    std::size_t line;
    std::string text;
  };
  std::vector<LocalGrid> localGrids_;
  std::map<Id, nastran::CoordCard> coordCards_;
  char coordType_ = 'R';
  std::string gridSetFile_;
  std::size_t gridSetLine_ = 0;
  std::string gridSetText_;
};

}  // namespace

FeModel readNastran(const std::filesystem::path& path, Warnings& warnings) {
  Reader reader(warnings);
  return reader.read(path);
}

}  // namespace voxremesh::io
