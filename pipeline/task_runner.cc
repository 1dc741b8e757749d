#include "pipeline/task_runner.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/sha256.h"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>

extern char **environ;

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  namespace
  {
    std::atomic<pid_t> running_child{0};

    void on_signal(const int sig)
    {
      interrupt_requested() = true;
      const pid_t child = running_child.load();
      if (child > 0)
        ::kill(-child, sig);  // the stage runs in its own process group (mpirun and its ranks)
    }

    std::string stamp_path(const std::string &dir) { return dir + "/.task.json"; }

    /// The wall time recorded when the task ran, if its stamp carries `identity`.
    std::optional<double> stamp_matches(const std::string &dir, const std::string &identity)
    {
      try
      {
        const auto j = parse_json_string(read_file(stamp_path(dir)), stamp_path(dir));
        if (j.at("identity").get<std::string>() == identity)
          return j.at("wall_time").at("value").get<double>();
      }
      catch (...)
      {
      }
      return std::nullopt;
    }

    /// The stages record output paths in their manifests as they wrote them, inside
    /// "<dir>.partial"; after the rename those paths are "<dir>". Rewrite them so a manifest
    /// never points at a directory that no longer exists.
    void repoint_manifests(const std::string &dir, const std::string &partial)
    {
      for (const auto &entry : fs::recursive_directory_iterator(dir))
      {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() ||
            !(name == "manifest.json" || (name.size() > 14 &&
                                          name.compare(name.size() - 14, 14, ".manifest.json") == 0)))
          continue;
        std::string text = read_file(entry.path().string());
        for (std::size_t p; (p = text.find(partial)) != std::string::npos;)
          text.replace(p, partial.size(), dir);
        write_file_atomically(entry.path().string(), text);
      }
    }

    /// Runs argv with stdout+stderr appended to log_path; returns the wait status.
    int spawn_and_wait(const std::vector<std::string> &words, const std::string &log_path)
    {
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                       O_WRONLY | O_CREAT | O_APPEND, 0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
      posix_spawnattr_t attr;
      posix_spawnattr_init(&attr);
      posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
      posix_spawnattr_setpgroup(&attr, 0);
      std::vector<char *> argv;
      for (const auto &w : words)
        argv.push_back(const_cast<char *>(w.c_str()));
      argv.push_back(nullptr);
      pid_t pid = 0;
      const int rc = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
      posix_spawn_file_actions_destroy(&actions);
      posix_spawnattr_destroy(&attr);
      if (rc != 0)
        throw NumericalError("cannot start '" + words[0] + "': " + std::strerror(rc));
      running_child = pid;
      if (interrupt_requested())
        ::kill(-pid, SIGTERM);
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
          break;
      running_child = 0;
      return status;
    }
  } // namespace

  std::atomic<bool> &interrupt_requested()
  {
    static std::atomic<bool> flag{false};
    return flag;
  }

  void install_signal_handlers()
  {
    // The common handler (also seen by run_plot_script, which then stops the report's plot.py)
    // with on_signal as its hook: the running stage gets the signal too.
    interrupt::install(on_signal);
  }

  int run_process(const std::vector<std::string> &words, const std::string &log_path)
  {
    return spawn_and_wait(words, log_path);
  }

  std::string compute_identity(const Task &t)
  {
    nlohmann::json j;
    j["stage"] = t.stage;
    j["executable_sha256"] = sha256_file(t.executable);
    j["args"] = t.args;
    j["inputs"] = nlohmann::json::array();
    for (const auto &f : t.input_files)
      j["inputs"].push_back(sha256_file(f));
    j["depends_on"] = t.depends_on;
    return sha256_hex(json_text(j, -1));
  }

  std::optional<TaskResult> find_completed(const Task &t)
  {
    const std::string identity = compute_identity(t);
    if (const auto seconds = stamp_matches(t.output_dir, identity))
      return TaskResult{TaskOutcome::reused, identity, *seconds};
    return std::nullopt;
  }

  TaskResult run_task(const Task &t, const bool force)
  {
    const std::string identity = compute_identity(t);
    if (const auto seconds = stamp_matches(t.output_dir, identity); !force && seconds)
    {
      log::info("  reused  " + t.name + "  (inputs unchanged)");
      return {TaskOutcome::reused, identity, *seconds};
    }
    const std::string partial = t.output_dir + ".partial";
    fs::remove_all(partial);
    fs::create_directories(partial);
    std::vector<std::string> words = t.launcher;
    words.push_back(t.executable);
    for (auto a : t.args)
    {
      for (std::size_t p; (p = a.find("{out}")) != std::string::npos;)
        a.replace(p, 5, partial);
      words.push_back(a);
    }
    // The log and the command line sit beside the partial folder while the stage runs (a stage
    // may replace its whole output folder), and move into the result when it succeeds.
    const std::string log_path = t.output_dir + ".log";
    const std::string command_path = t.output_dir + ".command.txt";
    fs::remove(log_path);
    {
      AtomicFile cmd(command_path);
      for (const auto &w : words)
        cmd.stream() << w << ' ';
      cmd.stream() << '\n';
      cmd.commit();
    }
    log::info("  running " + t.name + "  (log: " + log_path + ")");
    const auto start = std::chrono::steady_clock::now();
    const int status = spawn_and_wait(words, log_path);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (interrupt_requested())
      throw NumericalError("interrupted during " + t.name + "; its partial output is in " +
                           partial + " and will be redone on the next run");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
      std::string tail;
      try
      {
        const std::string all = read_file(log_path);
        tail = all.substr(all.size() > 2000 ? all.size() - 2000 : 0);
      }
      catch (...)
      {
      }
      throw NumericalError(t.stage + " failed in task " + t.name + " (exit status " +
                           std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                           "); its log " + log_path + " ends with:\n" + tail);
    }
    fs::remove_all(t.output_dir);
    fs::rename(partial, t.output_dir);
    fs::rename(log_path, t.output_dir + "/stage.log");
    fs::rename(command_path, t.output_dir + "/command.txt");
    repoint_manifests(t.output_dir, partial);
    const nlohmann::json stamp = {{"schema", "clearjoint.task/1"},
                                  {"task", t.name},
                                  {"identity", identity},
                                  {"wall_time", {{"value", seconds}, {"unit", "s"}}}};
    write_file_atomically(stamp_path(t.output_dir), json_text(stamp) + "\n");
    log::info("  done    " + t.name + "  in " + log::format_duration(seconds));
    return {TaskOutcome::ran, identity, seconds};
  }
} // namespace clearjoint::pipeline
