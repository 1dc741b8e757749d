#include "common/log.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace clearjoint::log
{
  namespace
  {
    std::atomic<int> current_level{static_cast<int>(Level::info)};
    std::atomic<unsigned int> warning_count{0};

    void emit(const Level l, const char *prefix, const std::string &message)
    {
      if (static_cast<int>(l) < current_level.load())
        return;
      std::cerr << prefix << message << '\n' << std::flush;
    }
  } // namespace

  void set_level(const Level l) { current_level = static_cast<int>(l); }
  Level level() { return static_cast<Level>(current_level.load()); }

  void debug(const std::string &m) { emit(Level::debug, "[debug] ", m); }
  void info(const std::string &m) { emit(Level::info, "", m); }
  void warning(const std::string &m)
  {
    ++warning_count;
    emit(Level::warning, "warning: ", m);
  }
  void error(const std::string &m) { emit(Level::error, "error: ", m); }
  unsigned int n_warnings() { return warning_count.load(); }

  std::string format_duration(const double seconds)
  {
    char buf[64];
    if (!std::isfinite(seconds) || seconds < 0)
      return "?";
    if (seconds < 60)
      std::snprintf(buf, sizeof(buf), "%.1f s", seconds);
    else if (seconds < 3600)
      std::snprintf(buf, sizeof(buf), "%d min %02d s", int(seconds) / 60, int(seconds) % 60);
    else
      std::snprintf(buf, sizeof(buf), "%d h %02d min", int(seconds) / 3600,
                    (int(seconds) % 3600) / 60);
    return buf;
  }

  Progress::Progress(std::string label, const double total, std::string unit,
                     const double min_interval_s)
    : label_(std::move(label))
    , unit_(std::move(unit))
    , total_(total > 0 ? total : 1.0)
    , min_interval_s_(min_interval_s)
    , start_(std::chrono::steady_clock::now())
    , last_print_(start_)
    , is_terminal_(isatty(STDERR_FILENO) != 0)
  {}

  Progress::~Progress() { finish(); }

  double Progress::fraction() const { return std::min(1.0, std::max(0.0, done_ / total_)); }

  double Progress::elapsed_seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  double Progress::eta_seconds() const
  {
    const double f = fraction();
    if (f <= 0.0)
      return -1.0;
    return elapsed_seconds() * (1.0 - f) / f;
  }

  void Progress::update(const double done)
  {
    if (finished_)
      return;
    done_ = done;
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_print_).count();
    const double interval = is_terminal_ ? 0.2 : min_interval_s_;
    if (since >= interval)
    {
      last_print_ = now;
      print(false);
    }
  }

  void Progress::finish()
  {
    if (finished_)
      return;
    finished_ = true;
    if (level() > Level::info)
      return;
    if (printed_ || elapsed_seconds() > 1.0)
      print(true);
  }

  void Progress::print(const bool final_line)
  {
    if (level() > Level::info)
      return;
    printed_ = true;
    const double t = elapsed_seconds();
    const double rate = t > 0 ? done_ / t : 0.0;
    char buf[256];
    if (final_line)
      std::snprintf(buf, sizeof(buf), "%s  %5.1f %%  %.3g %s/s  done in %s", label_.c_str(),
                    100.0 * fraction(), rate, unit_.c_str(), format_duration(t).c_str());
    else
      std::snprintf(buf, sizeof(buf), "%s  %5.1f %%  %.3g %s/s  ETA %s", label_.c_str(),
                    100.0 * fraction(), rate, unit_.c_str(),
                    format_duration(eta_seconds()).c_str());
    if (is_terminal_)
      std::cerr << '\r' << buf << "\033[K" << (final_line ? "\n" : "") << std::flush;
    else
      std::cerr << buf << '\n' << std::flush;
  }
} // namespace clearjoint::log
