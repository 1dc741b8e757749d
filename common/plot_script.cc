#include "common/plot_script.h"

#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"

#include <signal.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

extern char **environ;

namespace clearjoint
{
  std::string plot_script_path()
  {
    if (const char *env = std::getenv("CLEARJOINT_PLOT_SCRIPT"); env && *env)
      return env;
    return std::string(CLEARJOINT_SOURCE_DIR) + "/scripts/plot.py";
  }

  bool run_plot_script(const std::string &kind, const std::vector<std::string> &args)
  {
    // Debian's python3-matplotlib lives with /usr/bin/python3; a python3 earlier on PATH
    // (pyenv, conda) usually lacks it. $CLEARJOINT_PYTHON overrides both.
    std::string python = "python3";
    if (const char *env = std::getenv("CLEARJOINT_PYTHON"); env && *env)
      python = env;
    else if (access("/usr/bin/python3", X_OK) == 0)
      python = "/usr/bin/python3";
    std::vector<std::string> words = {python, plot_script_path(), kind};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char *> argv;
    for (auto &w : words)
      argv.push_back(w.data());
    argv.push_back(nullptr);
    // plot.py ends itself when we die (PR_SET_PDEATHSIG, scripts/plot.py): our pid.
    std::vector<std::string> env_text;
    for (char **e = environ; *e; ++e)
      if (std::strncmp(*e, "CLEARJOINT_PLOT_PARENT=", 23) != 0)
        env_text.emplace_back(*e);
    env_text.push_back("CLEARJOINT_PLOT_PARENT=" + std::to_string(::getpid()));
    std::vector<char *> envp;
    for (auto &e : env_text)
      envp.push_back(e.data());
    envp.push_back(nullptr);
    pid_t pid;
    const int rc = posix_spawnp(&pid, words[0].c_str(), nullptr, nullptr, argv.data(), envp.data());
    if (rc != 0)
    {
      log::warning("plots skipped: cannot start " + words[0] + ": " + std::string(std::strerror(rc)));
      return false;
    }
    interrupt::child_started(pid);  // a hard stop ends it too (common/interrupt.h)
    struct Forget
    {
      pid_t pid;
      ~Forget() { interrupt::child_ended(pid); }
    } forget{pid};
    if (interrupt::requested())  // the signal came before the child existed
      ::kill(pid, SIGTERM);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
    {
      if (errno != EINTR)
        return false;
      if (interrupt::requested())
      {
        // Stop the child first: an interrupted stage must not leave plot.py running.
        ::kill(pid, SIGTERM);
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        {
        }
        interrupt::throw_if_requested("while plotting (" + kind + ")");
      }
    }
    interrupt::throw_if_requested("while plotting (" + kind + ")");
    // plot.py exits 100 + errno when it cannot write its output (a full disk): that is the
    // stage's write error, not a missing matplotlib.
    if (WIFEXITED(status) && WEXITSTATUS(status) > 100 && is_write_failure(WEXITSTATUS(status) - 100))
    {
      const auto out = std::find(args.begin(), args.end(), "--output");
      throw WriteError(out != args.end() && out + 1 != args.end() ? *(out + 1) :
                       args.empty()                              ? kind :
                                                                   args.front(),
                       std::string(std::strerror(WEXITSTATUS(status) - 100)) + " (plot.py " +
                         kind + ")");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
      log::warning("plots failed: '" + words[1] + " " + kind +
                   "' exited with an error (the data files are complete; see the message above)");
      return false;
    }
    return true;
  }
} // namespace clearjoint
