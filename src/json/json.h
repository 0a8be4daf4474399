// A small strict JSON parser (RFC 8259, no extensions): the batch job files, and the tests that
// check the JSON the tools print.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace voxremesh::json {

/// A parsed JSON value.
struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string text;  ///< string value, or the literal of a number
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;  ///< in document order, keys unique
  std::size_t line = 0;  ///< 1-based line where the value starts in the document

  /// The member named `key`; throws std::runtime_error when there is none.
  const Json& operator[](const std::string& key) const;
  /// The member named `key`, or nullptr.
  const Json* find(const std::string& key) const;
  /// Member names in document order.
  std::vector<std::string> keys() const;
};

/// A syntax error: the message names the line and column.
class JsonError : public std::runtime_error {
 public:
  JsonError(const std::string& message, std::size_t line, std::size_t column);
  std::size_t line() const noexcept { return line_; }
  std::size_t column() const noexcept { return column_; }

 private:
  std::size_t line_;
  std::size_t column_;
};

/// Parses one complete JSON document (strict grammar: no comments, no trailing commas, no
/// duplicate keys, UTF-16 surrogate pairs in \u escapes joined).
/// Throws JsonError naming the line and column of the first error.
Json parseJson(const std::string& text);

/// Appends `s` as a JSON string literal (quotes included); bytes that are not valid UTF-8 are
/// taken as Latin-1.
void appendJsonString(std::string& out, std::string_view s);

/// `s` as a JSON string literal (appendJsonString).
std::string quote(const std::string& text);

}  // namespace voxremesh::json
