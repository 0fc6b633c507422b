#include "flexgait/core/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>

namespace flexgait {

ProgressBar::ProgressBar(double total, std::string unit, double already_done, bool tenths_when_not_tty)
    : total_(total),
      start_done_(already_done),
      unit_(std::move(unit)),
      tty_(isatty(STDERR_FILENO) != 0),
      tenths_(tenths_when_not_tty),
      start_(std::chrono::steady_clock::now()),
      last_(start_ - std::chrono::seconds(1)) {}

void ProgressBar::show(double done) {
  if ((!tty_ && !tenths_) || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool end = done >= total_;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double rate_done = done - start_done_;
  const double eta = rate_done > 0 ? seconds / rate_done * std::max(total_ - done, 0.0) : 0.0;
  if (!tty_) {  // a log file: one line per tenth
    const int tenth = total_ > 0 ? std::clamp(static_cast<int>(10 * done / total_), 0, 10) : 10;
    if (tenth <= tenths_shown_) return;
    tenths_shown_ = tenth;
    finished_ = end;
    fmt::print(stderr, "{:3d} % ({:.0f}/{:.0f} {}), {:.1f} s, ETA {:.0f} s\n", 10 * tenth, done, total_, unit_, seconds,
               eta);
    return;
  }
  if (!end && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  const int width = 30;
  const int filled = total_ > 0 ? std::clamp(static_cast<int>(width * done / total_), 0, width) : width;
  fmt::print(stderr, "\r[{}{}] {:.0f}/{:.0f} {}, {:.1f} s, ETA {:.0f} s ", std::string(filled, '#'),
             std::string(width - filled, '.'), done, total_, unit_, seconds, eta);
  if (end) {
    fmt::print(stderr, "\n");
    finished_ = true;
  }
}

}  // namespace flexgait
