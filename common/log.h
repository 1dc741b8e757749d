// Logging to stderr with a level prefix, and a progress line for long loops.
// Results go to files; the terminal gets what a person watching the run wants to see.
#pragma once

#include <chrono>
#include <string>

namespace clearjoint::log
{
  enum class Level { debug = 0, info = 1, warning = 2, error = 3, quiet = 4 };

  /// Messages below this level are dropped (default info; stages map -v / -q onto it).
  void set_level(Level level);
  Level level();

  void debug(const std::string &message);
  void info(const std::string &message);
  void warning(const std::string &message);
  void error(const std::string &message);

  /// Number of warnings issued so far (reported in manifests and summaries).
  unsigned int n_warnings();

  /// A progress line: "label  42.0 %  12.3 units/s  ETA 5 s". On a terminal it redraws one
  /// line in place; when stderr is not a terminal (CI, log files) it prints a plain line at
  /// most every `min_interval_s` seconds and at the end, so logs stay readable.
  class Progress
  {
  public:
    /// total: the amount of work (e.g. simulated seconds, increments); unit: its name.
    Progress(std::string label, double total, std::string unit, double min_interval_s = 2.0);
    ~Progress();

    /// Report that `done` (absolute, in [0, total]) has been reached.
    void update(double done);
    /// Print the final line (idempotent; the destructor calls it).
    void finish();

    double fraction() const;
    double elapsed_seconds() const;
    /// Estimated seconds left from the mean rate so far; negative when not yet known.
    double eta_seconds() const;

  private:
    void print(bool final_line);

    std::string label_, unit_;
    double total_, done_ = 0.0, min_interval_s_;
    std::chrono::steady_clock::time_point start_, last_print_;
    bool is_terminal_, finished_ = false, printed_ = false;
  };

  /// "1.5 s", "2 min 05 s", "1 h 02 min".
  std::string format_duration(double seconds);
} // namespace clearjoint::log
