// SIGINT/SIGTERM handling shared by every stage (issue 16 item 4). The first signal only sets a
// flag: the stage polls it at safe points (between integrator steps, after an FE increment,
// while waiting for a child such as plot.py), unwinds with Interrupted — destructors remove its
// temporary files and folders, children are stopped — and exits 128 + signal (130 for SIGINT,
// 143 for SIGTERM). Nothing is then left under a final name that was not complete before. A
// second signal ends the process at once (same exit code); what it leaves behind is named
// *.tmp.<pid> or *.partial and never looks complete.
//
// A stage may be far from its next safe point (an FE setup or a linear solve of a fine mesh
// takes tens of seconds; mpirun sends SIGKILL 1 s after SIGTERM). arm_hard_stop() starts a
// watchdog: if the stage has not ended `grace` seconds after the first signal (or at once on a
// second signal), it stops the registered children (plot.py), removes the registered temporary
// files and folders (Temporary), logs one line and ends the process with 128 + signal. So a
// stage notices a signal within `grace` even inside a solve, and leaves nothing behind.
#pragma once

#include <sys/types.h>

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

  /// Starts the watchdog (once; after install()). `program` names the process in its message;
  /// `announce` false keeps it silent (the MPI ranks other than 0).
  void arm_hard_stop(const std::string &program, double grace_seconds, bool announce = true);

  /// A file or folder (removed as a whole) that a hard stop removes while it is registered:
  /// a work folder "DIR.tmp.<pid>", a temporary file "<path>.tmp.<pid>".
  class Temporary
  {
  public:
    Temporary() = default;
    explicit Temporary(const std::string &path);
    ~Temporary();
    Temporary(const Temporary &) = delete;
    Temporary &operator=(const Temporary &) = delete;
    /// Registers `path` (forgetting the one registered before, if any).
    void set(const std::string &path);
    /// Forgets the path (it was renamed into place or removed).
    void release();

  private:
    long id_ = 0;
  };

  /// A child process (plot.py) that a hard stop sends SIGTERM to while it is registered.
  void child_started(pid_t pid);
  void child_ended(pid_t pid);
} // namespace clearjoint::interrupt
