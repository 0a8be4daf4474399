#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "voxremesh/progress.h"

namespace voxremesh {

std::string progressText(const std::string& stage, const std::string& item, double fraction) {
  if (!(fraction >= 0)) fraction = 0;  // NaN too
  if (fraction > 1) fraction = 1;
  char percent[16];
  std::snprintf(percent, sizeof percent, "[%3d%%] ", static_cast<int>(std::floor(fraction * 100)));
  std::string text = percent + stage;
  if (!item.empty()) text += ": " + item;
  return text;
}

ProgressLine::ProgressLine(std::FILE* stream, bool enabled, double minIntervalSeconds)
    : stream_(stream),
      enabled_(enabled && stream != nullptr),
      minInterval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(minIntervalSeconds))) {}

ProgressLine::~ProgressLine() {
  clear();
}

bool ProgressLine::isTerminal(std::FILE* stream) {
  return stream != nullptr && ::isatty(::fileno(stream)) == 1;
}

void ProgressLine::update(const std::string& stage, const std::string& item, double fraction) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  if (shown_ && fraction < 1 && now - lastDraw_ < minInterval_) return;
  lastDraw_ = now;
  shown_ = true;
  // \r back to the start, the text, then ESC[K erases what a longer previous line left.
  const std::string line = "\r" + progressText(stage, item, fraction) + "\x1b[K";
  std::fwrite(line.data(), 1, line.size(), stream_);
  std::fflush(stream_);
}

void ProgressLine::clear() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!shown_) return;
  std::fputs("\r\x1b[K", stream_);
  std::fflush(stream_);
  shown_ = false;
}

}  // namespace voxremesh
