// Small helpers shared by the tests: a fresh scratch directory per test, writing files,
// running an executable with its exit code — in the foreground, or in the background to be
// interrupted — and the message of the input error a call throws.
#pragma once

#include "common/error.h"

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>

#include <sys/wait.h>
#include <unistd.h>

namespace clearjoint::test_support
{
  /// A fresh, empty directory under the build tree, removed again at the end of the test.
  class ScratchDir
  {
  public:
    explicit ScratchDir(const std::string &name)
      : path_(std::filesystem::path(CLEARJOINT_BINARY_DIR) / "test_scratch" /
              (name + "_" + std::to_string(::getpid())))
    {
      std::filesystem::remove_all(path_);
      std::filesystem::create_directories(path_);
    }
    ~ScratchDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string &name) const { return (path_ / name).string(); }
    const std::filesystem::path &path() const { return path_; }

  private:
    std::filesystem::path path_;
  };

  inline void write_text(const std::string &path, const std::string &text)
  {
    std::ofstream(path) << text;
  }

  /// Runs a shell command line; returns its exit status (or -1 if it did not exit normally).
  /// Output goes to `log_path` so tests can check messages.
  inline int run_command(const std::string &command_line, const std::string &log_path)
  {
    const int status = std::system((command_line + " > '" + log_path + "' 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  /// Starts `exe` with `args` in the background, stdout and stderr to `log_path`, with extra
  /// environment entries ("NAME=value"); returns its pid (for kill() and wait_exit_code()).
  inline pid_t start_process(const std::string &exe, const std::vector<std::string> &args,
                             const std::string &log_path,
                             const std::vector<std::string> &env = {})
  {
    const pid_t pid = fork();
    if (pid == 0)
    {
      for (const auto &e : env)
        putenv(const_cast<char *>(e.c_str()));  // the child's own copy of `env`
      const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 1);
      dup2(fd, 2);
      std::vector<char *> argv = {const_cast<char *>(exe.c_str())};
      for (const auto &a : args)
        argv.push_back(const_cast<char *>(a.c_str()));
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    return pid;
  }

  /// Waits for a started process: its exit status, or -1 if it did not exit normally.
  inline int wait_exit_code(const pid_t pid)
  {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  inline std::string read_text(const std::string &path)
  {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  /// What input_error_of() returns when the call throws nothing.
  inline const std::string accepted = "(accepted)";

  /// The message of the InputError that `call()` throws, `accepted` if it throws none, and
  /// "(not an InputError) ..." for any other exception — so that a test of a bad input checks
  /// the message with EXPECT_NE(message.find(...), npos) << message, and a wrong outcome shows
  /// in the failure instead of ending the test.
  template <typename Call>
  std::string input_error_of(Call &&call)
  {
    try
    {
      call();
    }
    catch (const InputError &e)
    {
      return e.what();
    }
    catch (const std::exception &e)
    {
      return std::string("(not an InputError) ") + e.what();
    }
    return accepted;
  }
} // namespace clearjoint::test_support
