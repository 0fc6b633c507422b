#pragma once
/// \file progress.hpp
/// A progress bar on standard error, shown only when it is a terminal (CI logs stay clean).
#include <chrono>
#include <string>

namespace flexgait {

class ProgressBar {
 public:
  /// \param total work to do, in `unit`s (points, simulated seconds, ...)
  /// \param already_done work done before this run (a resumed sweep): not counted in the rate
  /// \param tenths_when_not_tty without a terminal, one line per 10 % (sweeps and campaigns);
  ///        otherwise nothing is shown off a terminal
  ProgressBar(double total, std::string unit, double already_done = 0, bool tenths_when_not_tty = false);
  /// Shows `done` of the total with the elapsed wall time and an estimate of the rest; redraws at
  /// most ten times a second except at the end.
  void show(double done);

 private:
  double total_;
  double start_done_;
  std::string unit_;
  bool tty_;
  bool tenths_;
  int tenths_shown_ = -1;  ///< without a terminal: the last tenth reported
  std::chrono::steady_clock::time_point start_, last_;
  bool finished_ = false;
};

}  // namespace flexgait
