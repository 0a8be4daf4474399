// A progress line for long runs on a terminal: "[ 42%] stage: item", redrawn in place with a
// carriage return, silent when the stream is not a terminal or the user asked for quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace voxremesh {

/// A single status line redrawn in place. All members are thread-safe.
class ProgressLine {
 public:
  /// @param stream   where to draw (stderr for the CLI)
  /// @param enabled  draw at all; pass isTerminal(stream) && !quiet
  /// @param minIntervalSeconds  redraw at most this often (an update reaching 100 % and the
  ///                 first update always draw)
  ProgressLine(std::FILE* stream, bool enabled, double minIntervalSeconds = 0.1);
  /// Erases the line if one is shown.
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// True when `stream` is a terminal (isatty).
  static bool isTerminal(std::FILE* stream);

  /// Shows "[ pp%] stage: item" with fraction clamped to [0, 1] (NaN shows 0 %).
  void update(const std::string& stage, const std::string& item, double fraction);

  /// Erases the shown line (so that other output starts on a clean line).
  void clear();

  /// True when the line draws at all.
  bool enabled() const { return enabled_; }

 private:
  std::FILE* stream_;
  bool enabled_;
  std::chrono::steady_clock::duration minInterval_;
  std::chrono::steady_clock::time_point lastDraw_{};
  bool shown_ = false;
  std::mutex mutex_;
};

/// The text of one progress line (without the carriage return and erase sequence), e.g.
/// "[ 42%] extract: part 4075". Exposed for tests.
std::string progressText(const std::string& stage, const std::string& item, double fraction);

}  // namespace voxremesh
