// Errors voxremesh reports to the user.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace voxremesh {

/// Bad input: a file that cannot be read as what it claims to be. Carries the file, the 1-based
/// line (0 when the error is not tied to a line) and the offending card or line text.
class InputError : public std::runtime_error {
 public:
  /// Builds "file:line: message" ("message" alone without file and line) and, when card is not
  /// empty, "\n  card: <card>".
  InputError(std::string file, std::size_t line, const std::string& message, std::string card = {});

  const std::string& file() const noexcept { return file_; }
  std::size_t line() const noexcept { return line_; }
  const std::string& card() const noexcept { return card_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string card_;
};

/// A setting outside its meaningful range (negative size, unknown option, ...).
class SettingError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace voxremesh
