// Runs the project's plotting script (scripts/plot.py, Python + matplotlib) on a stage's
// outputs. C++ never draws plots itself (STYLE.md).
#pragma once

#include <string>
#include <vector>

namespace clearjoint
{
  /// Path of scripts/plot.py: $CLEARJOINT_PLOT_SCRIPT if set, else the source tree's copy.
  std::string plot_script_path();

  /// Runs `/usr/bin/python3 plot.py <kind> <args...>` (or $CLEARJOINT_PYTHON); returns true on exit status 0. A failure (no
  /// python3, no matplotlib, a bad file) is logged as a warning: plots are a convenience on top
  /// of the stage's data files, which are already written.
  /// If an interrupt arrives (common/interrupt.h) the script is stopped (SIGTERM) and
  /// interrupt::Interrupted is thrown. If it cannot write its output (plot.py exits 100 +
  /// errno: a full disk, an I/O error) WriteError is thrown naming the output (the argument
  /// after "--output", else the first argument) and the OS reason.
  bool run_plot_script(const std::string &kind, const std::vector<std::string> &args);
} // namespace clearjoint
