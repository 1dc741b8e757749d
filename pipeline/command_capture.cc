#include "pipeline/command_capture.h"

#include "pipeline/spawn.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace clearjoint::pipeline
{
  CommandResult run_capture(const std::vector<std::string> &words, const double timeout_s)
  {
    CommandResult result;
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
    {
      result.start_error = std::string("pipe: ") + std::strerror(errno);
      return result;
    }
    SpawnOptions options;
    options.output_fd = fds[1];
    options.stdin_null = true;
    pid_t pid = 0;
    const int rc = spawn_in_new_group(words, options, pid);
    ::close(fds[1]);
    if (rc != 0)
    {
      ::close(fds[0]);
      result.start_error = std::strerror(rc);
      return result;
    }
    using clock = std::chrono::steady_clock;
    const auto deadline = clock::now() + std::chrono::duration<double>(timeout_s);
    char buffer[4096];
    // Bounded by the deadline: every pass either reads, sees the end of the output, or waits
    // at most until the deadline.
    for (;;)
    {
      const double left = std::chrono::duration<double>(deadline - clock::now()).count();
      if (left <= 0)
      {
        result.timed_out = true;
        break;
      }
      pollfd p = {fds[0], POLLIN, 0};
      const int ready = ::poll(&p, 1, int(std::min(left, 1.0) * 1000) + 1);
      if (ready < 0 && errno != EINTR)
        break;
      if (ready <= 0)
        continue;
      const ssize_t n = ::read(fds[0], buffer, sizeof(buffer));
      if (n < 0 && errno == EINTR)
        continue;
      if (n <= 0)
        break;  // end of output: the command closed it (exited)
      if (result.output.size() < (1u << 20))
        result.output.append(buffer, std::size_t(n));
    }
    ::close(fds[0]);
    // The output has ended; wait for the exit, still no longer than the deadline.
    int status = 0;
    bool exited = false;
    while (!result.timed_out)
    {
      const pid_t w = ::waitpid(pid, &status, WNOHANG);
      if (w == pid || (w < 0 && errno != EINTR))
      {
        exited = w == pid;
        break;
      }
      if (clock::now() >= deadline)
        result.timed_out = true;
      else
        ::usleep(10000);
    }
    ::kill(-pid, SIGKILL);  // a command past its time, or anything it left in its group
    if (!exited)
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
      {
      }
    if (exited && WIFEXITED(status))
      result.exit_code = WEXITSTATUS(status);
    return result;
  }

  std::optional<std::string> find_on_path(const std::string &name)
  {
    const char *path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':'))
    {
      const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
      if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate))
        return candidate.string();
    }
    return std::nullopt;
  }
} // namespace clearjoint::pipeline
