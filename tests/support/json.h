// A small strict JSON parser for the tests: checks that the JSON the tools print is valid and
// lets a test look at what it holds.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace voxremesh::test {

/// A parsed JSON value.
struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string text;  // string value, or the literal of a number
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;  // in document order

  /// The member named `key`; throws std::runtime_error when there is none.
  const Json& operator[](const std::string& key) const {
    for (const auto& [name, value] : members)
      if (name == key) return value;
    throw std::runtime_error("no key " + key);
  }
  /// Member names in document order.
  std::vector<std::string> keys() const {
    std::vector<std::string> names;
    for (const auto& member : members) names.push_back(member.first);
    return names;
  }
};

/// Parses one complete JSON document (strict grammar, no extensions).
/// Throws std::runtime_error naming the offset of the first error.
Json parseJson(const std::string& text);

}  // namespace voxremesh::test
