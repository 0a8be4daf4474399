#include "json/json.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace voxremesh::json {

namespace {

void appendHex4(std::string& out, unsigned value) {
  static const char digits[] = "0123456789abcdef";
  out += "\\u00";
  out += digits[(value >> 4) & 0xF];
  out += digits[value & 0xF];
}

// Length of the valid UTF-8 sequence at s[i] (2..4), or 0 when there is none.
std::size_t utf8Sequence(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t length = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF)
    length = 2;
  else if (c == 0xE0)
    length = 3, lo = 0xA0;
  else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF)
    length = 3;
  else if (c == 0xED)
    length = 3, hi = 0x9F;
  else if (c == 0xF0)
    length = 4, lo = 0x90;
  else if (c >= 0xF1 && c <= 0xF3)
    length = 4;
  else if (c == 0xF4)
    length = 4, hi = 0x8F;
  if (length == 0 || i + length > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return length;
}

class Parser {
 public:
  explicit Parser(const std::string& s) : s_(s) {}

  Json parseDocument() {
    Json value = parseValue(0);
    skip();
    if (i_ != s_.size()) fail("trailing content after the document");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) {
      if (s_[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw JsonError(what, line, column);
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  bool atEnd() const { return i_ >= s_.size(); }
  void expect(char c, const char* what) {
    skip();
    if (peek() != c) fail(std::string(what) + " expected");
    ++i_;
  }
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\t' || s_[i_] == '\r'))
      ++i_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  std::size_t lineHere() const {
    std::size_t line = 1;
    for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) line += s_[k] == '\n' ? 1 : 0;
    return line;
  }

  Json parseValue(int depth) {
    if (depth > 512) fail("nesting deeper than 512 levels");
    skip();
    if (atEnd()) fail("unexpected end of the document");
    Json v;
    v.line = lineHere();
    const char c = peek();
    if (c == '{') {
      v.type = Json::Type::Object;
      ++i_;
      skip();
      if (peek() == '}') return ++i_, v;
      for (;;) {
        skip();
        if (peek() != '"') fail("a key in double quotes expected");
        std::string key = parseString();
        for (const auto& member : v.members)
          if (member.first == key) fail("duplicate key \"" + key + "\"");
        expect(':', "':'");
        v.members.emplace_back(key, parseValue(depth + 1));
        skip();
        if (peek() == ',') {
          ++i_;
        } else if (peek() == '}') {
          return ++i_, v;
        } else {
          fail("',' or '}' expected");
        }
      }
    }
    if (c == '[') {
      v.type = Json::Type::Array;
      ++i_;
      skip();
      if (peek() == ']') return ++i_, v;
      for (;;) {
        v.items.push_back(parseValue(depth + 1));
        skip();
        if (peek() == ',') {
          ++i_;
        } else if (peek() == ']') {
          return ++i_, v;
        } else {
          fail("',' or ']' expected");
        }
      }
    }
    if (c == '"') {
      v.type = Json::Type::String;
      v.text = parseString();
      return v;
    }
    if (literal("null")) return v;
    if (literal("true") || literal("false")) {
      v.type = Json::Type::Bool;
      v.boolean = s_[i_ - 1] == 'e' && s_[i_ - 2] == 'u';
      return v;
    }
    // number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
    const std::size_t start = i_;
    const auto digits = [&] {
      const std::size_t from = i_;
      while (std::isdigit(static_cast<unsigned char>(peek()))) ++i_;
      if (i_ == from) fail("a value expected");
    };
    if (peek() == '-') ++i_;
    if (peek() == '0') {
      ++i_;
    } else {
      digits();
    }
    if (peek() == '.') ++i_, digits();
    if (peek() == 'e' || peek() == 'E') {
      ++i_;
      if (peek() == '+' || peek() == '-') ++i_;
      digits();
    }
    v.type = Json::Type::Number;
    v.text = s_.substr(start, i_ - start);
    v.number = std::strtod(v.text.c_str(), nullptr);
    return v;
  }

  unsigned hex4() {
    if (i_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned code = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = s_[i_++];
      code <<= 4;
      if (h >= '0' && h <= '9') {
        code |= static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        code |= static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        code |= static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("bad hex digit in \\u escape");
      }
    }
    return code;
  }

  static void appendUtf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  std::string parseString() {
    ++i_;  // opening quote
    std::string out;
    for (;;) {
      if (atEnd()) fail("unterminated string");
      const unsigned char c = static_cast<unsigned char>(s_[i_++]);
      if (c == '"') return out;
      if (c < 0x20) fail("raw control character in a string");
      if (c != '\\') {
        out += static_cast<char>(c);
        continue;
      }
      if (atEnd()) fail("unterminated string");
      const char e = s_[i_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = hex4();
          if (code >= 0xDC00 && code < 0xE000) fail("unpaired low surrogate in \\u escape");
          if (code >= 0xD800 && code < 0xDC00) {
            if (!literal("\\u")) fail("unpaired high surrogate in \\u escape");
            const unsigned low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("unpaired high surrogate in \\u escape");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          appendUtf8(out, code);
          break;
        }
        default:
          fail("bad escape '\\" + std::string(1, e) + "'");
      }
    }
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

}  // namespace

const Json& Json::operator[](const std::string& key) const {
  if (const Json* value = find(key)) return *value;
  throw std::runtime_error("no key " + key);
}

const Json* Json::find(const std::string& key) const {
  for (const auto& [name, value] : members)
    if (name == key) return &value;
  return nullptr;
}

std::vector<std::string> Json::keys() const {
  std::vector<std::string> names;
  for (const auto& member : members) names.push_back(member.first);
  return names;
}

JsonError::JsonError(const std::string& message, std::size_t line, std::size_t column)
    : std::runtime_error("JSON line " + std::to_string(line) + ", column " +
                         std::to_string(column) + ": " + message),
      line_(line),
      column_(column) {}

Json parseJson(const std::string& text) {
  return Parser(text).parseDocument();
}

void appendJsonString(std::string& out, std::string_view s) {
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '"':
          out += "\\\"";
          break;
        case '\\':
          out += "\\\\";
          break;
        case '\b':
          out += "\\b";
          break;
        case '\f':
          out += "\\f";
          break;
        case '\n':
          out += "\\n";
          break;
        case '\r':
          out += "\\r";
          break;
        case '\t':
          out += "\\t";
          break;
        default:
          if (c < 0x20)
            appendHex4(out, c);
          else
            out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    const std::size_t length = utf8Sequence(s, i);
    if (length == 0) {
      appendHex4(out, c);  // Latin-1 byte: the code point equals the byte
      ++i;
    } else {
      out.append(s.substr(i, length));
      i += length;
    }
  }
  out += '"';
}

std::string quote(const std::string& text) {
  std::string out;
  appendJsonString(out, text);
  return out;
}

}  // namespace voxremesh::json
