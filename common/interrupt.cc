#include "common/interrupt.h"

#include <csignal>
#include <cstring>

#include <unistd.h>

namespace clearjoint::interrupt
{
  namespace
  {
    volatile std::sig_atomic_t received = 0;
    void (*volatile user_hook)(int) = nullptr;

    void on_signal(const int sig)
    {
      if (user_hook)
        user_hook(sig);
      if (received != 0)
        ::_exit(128 + received);  // second signal: the user insists
      received = sig;
    }
  } // namespace

  void install(void (*hook)(int))
  {
    user_hook = hook;
    struct sigaction sa;
    std::memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;  // no SA_RESTART: waitpid() & co. return EINTR and we look at the flag
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
  }

  int signal_received() { return received; }
  bool requested() { return received != 0; }
  int exit_code() { return received != 0 ? 128 + received : 0; }
  void reset() { received = 0; }

  Interrupted::Interrupted(const std::string &where)
    : std::runtime_error(std::string("interrupted by ") +
                         (signal_received() == SIGTERM ? "SIGTERM" : "SIGINT") +
                         (where.empty() ? "" : " " + where))
  {}

  void throw_if_requested(const std::string &where)
  {
    if (requested())
      throw Interrupted(where);
  }
} // namespace clearjoint::interrupt
