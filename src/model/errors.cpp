#include "voxremesh/errors.h"

#include <utility>

namespace voxremesh {

namespace {

std::string describe(const std::string& file, std::size_t line, const std::string& message,
                     const std::string& card) {
  std::string text = file;
  if (line > 0) text += ":" + std::to_string(line);
  text += text.empty() ? message : ": " + message;  // no location: the message alone
  if (!card.empty()) text += "\n  card: " + card;
  return text;
}

}  // namespace

InputError::InputError(std::string file, std::size_t line, const std::string& message,
                       std::string card)
    : std::runtime_error(describe(file, line, message, card)),
      file_(std::move(file)),
      line_(line),
      card_(std::move(card)) {}

}  // namespace voxremesh
