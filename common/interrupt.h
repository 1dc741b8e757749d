// SIGINT/SIGTERM handling shared by every stage (issue 16 item 4). The first signal only sets a
// flag: the stage polls it at safe points (between integrator steps, after an FE increment,
// while waiting for a child such as plot.py), unwinds with Interrupted — destructors remove its
// temporary files and folders, children are stopped — and exits 128 + signal (130 for SIGINT,
// 143 for SIGTERM). Nothing is then left under a final name that was not complete before. A
// second signal ends the process at once (same exit code); what it leaves behind is named
// *.tmp.<pid> or *.partial and never looks complete.
#pragma once

#include <stdexcept>
#include <string>

namespace clearjoint::interrupt
{
  /// Installs the handlers (without SA_RESTART, so a blocking wait returns EINTR). `hook`, if
  /// given, is called from the handler with the signal number (async-signal-safe code only),
  /// e.g. to pass the signal on to a child's process group.
  void install(void (*hook)(int) = nullptr);

  /// The first signal received, or 0.
  int signal_received();
  bool requested();
  /// 128 + the signal (130 SIGINT, 143 SIGTERM).
  int exit_code();

  class Interrupted : public std::runtime_error
  {
  public:
    explicit Interrupted(const std::string &where);
  };

  /// Throws Interrupted("interrupted by SIGINT <where>") if a signal arrived.
  void throw_if_requested(const std::string &where);

  /// For tests: forget an earlier signal.
  void reset();
} // namespace clearjoint::interrupt
