#include "common/interrupt.h"

#include "common/log.h"

#include <semaphore.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <thread>

namespace clearjoint::interrupt
{
  namespace
  {
    volatile std::sig_atomic_t received = 0;
    volatile std::sig_atomic_t n_received = 0;
    void (*volatile user_hook)(int) = nullptr;

    // The watchdog (arm_hard_stop): woken by the handler through a semaphore (sem_post is
    // async-signal-safe). Everything it uses is allocated once and never destroyed, so a
    // watchdog that wakes while the process is exiting finds it still there.
    sem_t wake;
    std::atomic<bool> armed{false};

    struct Registry
    {
      std::mutex mutex;
      long next_id = 1;
      std::map<long, std::string> paths;
      std::set<pid_t> children;
    };
    Registry &registry()
    {
      static Registry *r = new Registry;
      return *r;
    }

    const char *signal_name(const int sig) { return sig == SIGTERM ? "SIGTERM" : "SIGINT"; }

    void on_signal(const int sig)
    {
      if (user_hook)
        user_hook(sig);
      n_received = n_received + 1;
      if (received == 0)
        received = sig;
      else if (!armed.load() || n_received > 2)
        ::_exit(128 + received);  // the user insists (with a watchdog: the third signal)
      if (armed.load())
        ::sem_post(&wake);
    }

    /// Waits for `seconds` or until the semaphore is posted again (a second signal).
    void wait_or_wake(const double seconds)
    {
      timespec until;
      ::clock_gettime(CLOCK_REALTIME, &until);
      const long ns = until.tv_nsec + long((seconds - double(long(seconds))) * 1e9);
      until.tv_sec += long(seconds) + ns / 1000000000L;
      until.tv_nsec = ns % 1000000000L;
      while (::sem_timedwait(&wake, &until) != 0 && errno == EINTR)
      {
      }
    }

    void watchdog(const std::string program, const double grace, const bool announce)
    {
      // Signals go to the other threads (a blocking wait there must see EINTR).
      sigset_t block;
      sigemptyset(&block);
      sigaddset(&block, SIGINT);
      sigaddset(&block, SIGTERM);
      pthread_sigmask(SIG_BLOCK, &block, nullptr);
      while (::sem_wait(&wake) != 0 && errno == EINTR)
      {
      }
      wait_or_wake(grace);
      // Still running: stop at once. The registry's lock is taken with a time limit (the main
      // thread holds it only for a moment; a thread killed inside it must not hang us).
      auto &r = registry();
      std::unique_lock<std::mutex> lock(r.mutex, std::defer_lock);
      for (int k = 0; k < 100 && !lock.try_lock(); ++k)
        ::usleep(1000);
      std::string removed;
      for (const pid_t child : r.children)
        ::kill(child, SIGTERM);
      for (const auto &[id, path] : r.paths)
      {
        std::error_code ec;
        // A file being created under it while we remove it (another thread): try again.
        for (int k = 0; k < 5 && std::filesystem::exists(path, ec); ++k)
          std::filesystem::remove_all(path, ec);
        bool inside = false;  // a temporary file inside a folder named already
        for (const auto &[other_id, other] : r.paths)
          inside = inside || (other_id != id && path.compare(0, other.size() + 1, other + "/") == 0);
        if (!inside)
          removed += (removed.empty() ? "" : ", ") + path;
      }
      if (announce)
        log::error(program + ": interrupted by " + signal_name(received) +
                   " during a step that did not end within " + log::format_duration(grace) +
                   ": stopped at once" +
                   (removed.empty() ? std::string() : "; removed " + removed) +
                   ", earlier outputs left as they were");
      ::_exit(128 + (received != 0 ? received : SIGTERM));
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

  void arm_hard_stop(const std::string &program, const double grace_seconds, const bool announce)
  {
    if (armed.exchange(true))
      return;
    ::sem_init(&wake, 0, 0);
    registry();  // made before any signal
    std::thread(watchdog, program, grace_seconds, announce).detach();
    if (received != 0)  // a signal before the watchdog existed
      ::sem_post(&wake);
  }

  int signal_received() { return received; }
  bool requested() { return received != 0; }
  int exit_code() { return received != 0 ? 128 + received : 0; }
  void reset()
  {
    received = 0;
    n_received = 0;
  }

  Interrupted::Interrupted(const std::string &where)
    : std::runtime_error(std::string("interrupted by ") + signal_name(signal_received()) +
                         (where.empty() ? "" : " " + where))
  {}

  void throw_if_requested(const std::string &where)
  {
    if (requested())
      throw Interrupted(where);
  }

  Temporary::Temporary(const std::string &path) { set(path); }
  Temporary::~Temporary() { release(); }

  void Temporary::set(const std::string &path)
  {
    auto &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    if (id_ != 0)
      r.paths.erase(id_);
    id_ = r.next_id++;
    r.paths[id_] = path;
  }

  void Temporary::release()
  {
    if (id_ == 0)
      return;
    auto &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.paths.erase(id_);
    id_ = 0;
  }

  void child_started(const pid_t pid)
  {
    auto &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.children.insert(pid);
  }

  void child_ended(const pid_t pid)
  {
    auto &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.children.erase(pid);
  }
} // namespace clearjoint::interrupt
