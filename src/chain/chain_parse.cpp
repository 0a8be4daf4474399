// Parsing action chains: prefix matching of actions and options, typed values, config files,
// formatting a chain back into a config file, and the help text (see action_chain.h).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <string>

#include "io/text_scan.h"
#include "voxremesh/action_chain.h"
#include "voxremesh/errors.h"

namespace voxremesh::chain {

namespace {

std::string joinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// Unique-prefix match of `word` among `names`: the exact name, else the only name starting with
/// it. Returns the index or throws SettingError (with `what` naming the kind of name).
std::size_t matchPrefix(const std::string& word, const std::vector<std::string>& names,
                        const std::string& what, const std::string& dash) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == word) return i;
    if (!word.empty() && names[i].compare(0, word.size(), word) == 0) candidates.push_back(i);
  }
  if (candidates.size() == 1) return candidates[0];
  std::vector<std::string> listed;
  if (candidates.empty()) {
    for (const auto& name : names) listed.push_back(dash + name);
    throw SettingError(
        "unknown " + what + " '" + dash + word + "' (" +
        (listed.empty() ? std::string("it takes no options") : "one of " + joinNames(listed)) +
        ")");
  }
  for (const std::size_t i : candidates) listed.push_back(dash + names[i]);
  throw SettingError("ambiguous " + what + " '" + dash + word + "': it could be " +
                     joinNames(listed));
}

bool parseDouble(const std::string& text, double& value) {
  errno = 0;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && errno != ERANGE &&
         std::isfinite(value);
}

bool parseWhole(const std::string& text, long long& value) {
  errno = 0;
  char* end = nullptr;
  value = std::strtoll(text.c_str(), &end, 10);
  return !text.empty() && end == text.c_str() + text.size() && errno != ERANGE;
}

const char* typeName(OptionType type) {
  switch (type) {
    case OptionType::Number:
      return "a number";
    case OptionType::Integer:
      return "a whole number";
    case OptionType::Flag:
      return "0 or 1";
    case OptionType::Text:
      break;
  }
  return "text";
}

/// A word of the chain with where it came from.
struct Word {
  std::string text;
  std::string origin;
  bool quoted = false;  ///< starts with a double quote (config files): never an action
  std::size_t equals = std::string::npos;  ///< the first '=' outside quotes
};

/// True for a word that starts an action: '-' followed by a letter.
bool isActionWord(const Word& word) {
  return !word.quoted && word.text.size() >= 2 && word.text[0] == '-' &&
         std::isalpha(static_cast<unsigned char>(word.text[1]));
}

Chain parseWords(const std::vector<Word>& words, std::set<std::string>& configStack);

/// Splits a config line into words: blanks separate, double quotes keep blanks, '#' outside
/// quotes ends the line. Throws InputError for an unterminated quote.
std::vector<Word> splitConfigLine(std::string_view line, const std::string& file,
                                  std::size_t number) {
  std::vector<Word> words;
  const std::string origin = file + ":" + std::to_string(number);
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size() || line[i] == '#') break;
    Word word{{}, origin, line[i] == '"'};
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
      if (line[i] == '"') {
        const std::size_t close = line.find('"', i + 1);
        if (close == std::string_view::npos)
          throw InputError(file, number, "unterminated double quote", std::string(line));
        word.text += line.substr(i + 1, close - i - 1);
        i = close + 1;
        continue;
      }
      if (line[i] == '=' && word.equals == std::string::npos) word.equals = word.text.size();
      word.text += line[i++];
    }
    words.push_back(std::move(word));
  }
  return words;
}

/// The actions of the config file `path` (its -config lines replaced by the actions of the files
/// they name). `configStack` holds the config files being read, to refuse a cycle. Throws
/// InputError at a line of the file; an error about a whole included file (missing, or already
/// being read) is located at the -config line that includes it.
Chain parseConfigFile(const std::filesystem::path& path, std::set<std::string>& configStack) {
  const std::string name = path.string();
  std::error_code ignored;
  const std::string key = std::filesystem::weakly_canonical(path, ignored).string();
  if (!configStack.insert(key).second)
    throw InputError(name, 0, "config file includes itself (through -config)");
  const std::string content = io::loadFile(path);
  Chain chain;
  io::LineCursor cursor(content);
  while (cursor.next()) {
    std::vector<Word> words = splitConfigLine(cursor.line(), name, cursor.lineNumber());
    if (words.empty()) continue;
    if (!isActionWord(words[0]) && !words[0].quoted) words[0].text = "-" + words[0].text;
    for (std::size_t w = 1; w < words.size(); ++w)
      if (isActionWord(words[w]))
        throw InputError(name, cursor.lineNumber(),
                         "one action per line: '" + words[w].text + "' starts a second one",
                         std::string(cursor.line()));
    try {
      Chain line = parseWords(words, configStack);
      for (ActionCall& call : line) chain.push_back(std::move(call));
    } catch (const SettingError& error) {
      throw InputError(name, cursor.lineNumber(), error.what(), std::string(cursor.line()));
    } catch (const InputError& error) {
      // An included config file as a whole (it has no line): name this file and line too.
      if (error.line() != 0) throw;
      throw InputError(name, cursor.lineNumber(), error.what(), std::string(cursor.line()));
    }
  }
  configStack.erase(key);
  return chain;
}

void setValue(ActionCall& call, const OptionDef& option, const std::string& value,
              const std::string& origin) {
  const std::string where = "-" + call.action->name + " " + option.name + " (" + origin + ")";
  double number = 0;
  long long whole = 0;
  switch (option.type) {
    case OptionType::Number:
      if (!parseDouble(value, number))
        throw SettingError(where + " expects a number, not '" + value + "'");
      break;
    case OptionType::Integer:
      if (!parseWhole(value, whole))
        throw SettingError(where + " expects a whole number, not '" + value + "'");
      break;
    case OptionType::Flag:
      if (value != "0" && value != "1" && value != "true" && value != "false")
        throw SettingError(where + " expects 0 or 1, not '" + value + "'");
      break;
    case OptionType::Text:
      if (value.empty()) throw SettingError(where + " needs a value");
      break;
  }
  if (call.has(option.name)) throw SettingError(where + " is given twice");
  call.values[option.name] = value;
  call.given[option.name] = true;
}

Chain parseWords(const std::vector<Word>& words, std::set<std::string>& configStack) {
  Chain chain;
  std::vector<std::string> actionNames;
  for (const ActionDef& action : actions()) actionNames.push_back(action.name);
  std::size_t i = 0;
  while (i < words.size()) {
    const Word& word = words[i];
    if (!isActionWord(word))
      throw SettingError("'" + word.text + "' (" + word.origin +
                         ") is not an action; actions start with '-' (see -help)");
    const ActionDef* action = nullptr;
    try {
      action = &actions()[matchPrefix(word.text.substr(1), actionNames, "action", "-")];
    } catch (const SettingError& error) {
      throw SettingError(std::string(error.what()) + " (" + word.origin + ")");
    }
    ++i;
    ActionCall call;
    call.action = action;
    call.origin = word.origin;
    std::vector<std::string> optionNames;
    for (const OptionDef& option : action->options) optionNames.push_back(option.name);
    for (; i < words.size() && !isActionWord(words[i]); ++i) {
      const std::string& text = words[i].text;
      const std::size_t equals = words[i].equals;
      if (equals == std::string::npos) {
        if (action->positional.empty() || call.has(action->positional))
          throw SettingError("-" + action->name + " (" + word.origin + ") does not take '" + text +
                             "'; give options as key=value (-help " + action->name + ")");
        for (const OptionDef& option : action->options)
          if (option.name == action->positional) setValue(call, option, text, words[i].origin);
        continue;
      }
      const OptionDef* option = nullptr;
      try {
        option = &action->options[matchPrefix(text.substr(0, equals), optionNames,
                                              "option of -" + action->name, "")];
      } catch (const SettingError& error) {
        throw SettingError(std::string(error.what()) + " (" + words[i].origin + ")");
      }
      setValue(call, *option, text.substr(equals + 1), words[i].origin);
    }
    for (const OptionDef& option : action->options) {
      if (call.has(option.name)) continue;
      if (option.required)
        throw SettingError("-" + action->name + " (" + word.origin + ") needs " + option.name +
                           "=... (" + option.help + ")");
      call.values[option.name] = option.defaultValue;
      call.given[option.name] = false;
    }
    if (action->name == "config") {
      Chain inserted = parseConfigFile(call.text("file"), configStack);
      for (ActionCall& c : inserted) chain.push_back(std::move(c));
      continue;
    }
    chain.push_back(std::move(call));
  }
  return chain;
}

std::string quoteIfNeeded(const std::string& value) {
  if (value.find_first_of(" \t#\"") == std::string::npos && !value.empty()) return value;
  return "\"" + value + "\"";
}

}  // namespace

bool ActionCall::has(const std::string& option) const {
  const auto it = given.find(option);
  return it != given.end() && it->second;
}

const std::string& ActionCall::text(const std::string& option) const {
  static const std::string kEmpty;
  const auto it = values.find(option);
  return it == values.end() ? kEmpty : it->second;
}

double ActionCall::number(const std::string& option) const {
  double value = 0;
  parseDouble(text(option), value);
  return value;
}

long long ActionCall::integer(const std::string& option) const {
  long long value = 0;
  parseWhole(text(option), value);
  return value;
}

bool ActionCall::flag(const std::string& option) const {
  return text(option) == "1" || text(option) == "true";
}

const ActionDef& findAction(const std::string& word) {
  std::vector<std::string> names;
  for (const ActionDef& action : actions()) names.push_back(action.name);
  return actions()[matchPrefix(word, names, "action", "-")];
}

Chain parseChain(const std::vector<std::string>& args) {
  std::vector<Word> words;
  for (std::size_t i = 0; i < args.size(); ++i)
    words.push_back(Word{args[i], "argument " + std::to_string(i + 1), false, args[i].find('=')});
  std::set<std::string> configStack;
  return parseWords(words, configStack);
}

Chain parseConfig(const std::filesystem::path& path) {
  std::set<std::string> configStack;
  return parseConfigFile(path, configStack);
}

std::string formatChain(const Chain& chain) {
  std::string text = "# voxremesh action chain: one action per line (voxremesh -config FILE)\n";
  for (const ActionCall& call : chain) {
    if (call.action->name == "save-chain") continue;
    text += "-" + call.action->name;
    for (const OptionDef& option : call.action->options)
      if (call.has(option.name))
        text += " " + option.name + "=" + quoteIfNeeded(call.text(option.name));
    text += "\n";
  }
  return text;
}

std::string chainHelp(const std::string& actionName) {
  if (actionName.empty()) {
    std::string text =
        "usage: voxremesh -ACTION [key=value ...] -ACTION ...\n\n"
        "Runs actions left to right on a stack of decks, quad meshes and volumes. Action and\n"
        "option names may be shortened to a unique prefix; -config FILE runs the actions of a\n"
        "file (one per line, '#' comments).\n\nactions:\n";
    for (const ActionDef& action : actions()) {
      std::string name = "  -" + action.name;
      name.resize(std::max<std::size_t>(name.size() + 1, 14), ' ');
      text += name + action.summary + "\n";
    }
    text += "\n  -help ACTION  the options of one action\n";
    return text;
  }
  const ActionDef& action = findAction(actionName);
  std::string text = "-" + action.name + ": " + action.summary + "\n";
  if (!action.help.empty()) text += "\n" + action.help;
  if (!action.options.empty()) text += "\noptions:\n";
  for (const OptionDef& option : action.options) {
    std::string line = "  " + option.name + "=";
    line.resize(std::max<std::size_t>(line.size() + 1, 14), ' ');
    line += option.help + " (" + typeName(option.type);
    if (option.required) line += ", required";
    if (!option.defaultValue.empty()) line += ", default " + option.defaultValue;
    if (option.name == action.positional) line += "; may be given without " + option.name + "=";
    text += line + ")\n";
  }
  return text;
}

}  // namespace voxremesh::chain
