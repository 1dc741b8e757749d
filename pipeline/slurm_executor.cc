#include "pipeline/slurm_executor.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/log.h"
#include "pipeline/task_runner.h"

#include <time.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  namespace
  {
    /// Our name for a job PENDING with reason "launch failed requeued held".
    const std::string launch_failed = "LAUNCH_FAILED";

    /// Squeue states after which a job does nothing more (Slurm's JOB_STATE_BASE ends). A
    /// PREEMPTED job that the site requeues shows PENDING again, and is waited for.
    const std::set<std::string> final_states = {"COMPLETED", "FAILED",        "CANCELLED",
                                                "TIMEOUT",   "NODE_FAIL",     "PREEMPTED",
                                                "BOOT_FAIL", "OUT_OF_MEMORY", "DEADLINE",
                                                launch_failed};

    std::string shell_quote(const std::string &word)
    {
      std::string q = "'";
      for (const char c : word)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      return q + "'";
    }

    std::string trimmed(std::string s)
    {
      while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.pop_back();
      std::size_t b = 0;
      while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b])))
        ++b;
      return s.substr(b);
    }

    std::optional<int> read_exit_file(const std::string &path)
    {
      std::ifstream in(path);
      int code = -1;
      if (in >> code)
        return code;
      return std::nullopt;
    }

    /// Sleeps `seconds`; false if a signal cut it short.
    bool sleep_for(const double seconds)
    {
      timespec t{time_t(seconds), long((seconds - std::floor(seconds)) * 1e9)};
      return ::nanosleep(&t, nullptr) == 0;
    }

    std::string what_state_means(const std::string &state)
    {
      if (state == "TIMEOUT")
        return " (its time limit was reached: raise executor.time_margin or the preset's "
               "measured time)";
      if (state == "CANCELLED")
        return " (scancel from outside run_pipeline, or the site cancelled it)";
      if (state == "NODE_FAIL" || state == "BOOT_FAIL")
        return " (a node failed; rerun run_pipeline to redo the task)";
      if (state == "PREEMPTED")
        return " (preempted and not requeued; rerun run_pipeline to redo the task)";
      if (state == launch_failed)
        return " (the node could not start it, see slurmd's log; it was requeued held and is "
               "cancelled)";
      if (state == "OUT_OF_MEMORY")
        return " (out of memory: give executor.sbatch_args a larger --mem)";
      return "";
    }
  } // namespace

  SlurmExecutor::SlurmExecutor(SlurmSettings settings, const int jobs)
    : settings_(std::move(settings))
    , jobs_(jobs)
  {}

  SlurmExecutor::~SlurmExecutor()
  {
    if (jobs_running_.empty())
      return;
    try
    {
      stop_all();
    }
    catch (...)
    {
    }
  }

  CommandResult SlurmExecutor::run(const std::vector<std::string> &words) const
  {
    return run_capture(words, settings_.command_timeout);
  }

  void SlurmExecutor::check_available(const SlurmSettings &settings, const std::string &file)
  {
    for (const std::string command : {"sbatch", "squeue", "scancel"})
      if (!find_on_path(command))
        throw InputError(file, "executor.kind", "slurm",
                         "local, or slurm with the Slurm commands on PATH",
                         "'" + command + "' is not on PATH (Debian package slurm-client)");
    const CommandResult r =
      run_capture({"squeue", "--noheader", "--format=%i", "--jobs=1"}, settings.command_timeout);
    // squeue exits 1 with "Invalid job id specified" for a job that does not exist: the
    // controller answered. Anything else (no answer, a refused connection) is an error.
    const bool answered = r.exit_code == 0 ||
                          (r.exit_code == 1 && r.output.find("Invalid job id") != std::string::npos);
    if (!answered)
      throw InputError(file, "executor.kind", "slurm", "a Slurm controller that answers",
                       "'squeue' " +
                         (r.timed_out ? "did not answer within " +
                                          std::to_string(int(settings.command_timeout)) +
                                          " s (executor.command_timeout)"
                                      : "failed (exit " + std::to_string(r.exit_code) + ")") +
                         ": " + trimmed(r.output.substr(0, 500)));
  }

  std::vector<std::string> SlurmExecutor::launcher(const int ranks) const
  {
    if (ranks <= 1)
      return {};
    if (settings_.mpi_launcher == "srun")
      return {"srun", "--mpi=" + settings_.srun_mpi, "-n", std::to_string(ranks)};
    // Open MPI's mpirun reads the job's allocation (SLURM_* variables) and starts its daemons
    // with srun; -np makes the ranks explicit. --allow-run-as-root for clusters run as root.
    return {"mpirun", "--allow-run-as-root", "-np", std::to_string(ranks)};
  }

  int SlurmExecutor::time_limit_minutes(const double expected_seconds) const
  {
    if (!(expected_seconds > 0))
      return int(std::ceil(settings_.time_unmeasured));
    return std::max(1, int(std::ceil(expected_seconds * settings_.time_margin / 60.0)));
  }

  void SlurmExecutor::cancel_earlier_job(const std::string &work_prefix)
  {
    // A job of an earlier run_pipeline that was killed (SIGKILL, a login node rebooted) may
    // still run and write into this task's .partial folder: end it before a new one starts.
    const std::string record = work_prefix + ".job.json";
    std::string id;
    try
    {
      id = nlohmann::json::parse(read_file(record)).at("job_id").get<std::string>();
    }
    catch (...)
    {
      return;  // none, or unreadable: nothing to cancel
    }
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      return;
    const auto state_of = [&]() {
      const CommandResult r = run({"squeue", "--noheader", "--states=all", "--format=%T", "--jobs=" + id});
      return trimmed(r.output.substr(0, r.output.find('\n')));
    };
    std::string state = state_of();
    if (state.empty() || final_states.count(state) || state.find("Invalid") != std::string::npos ||
        state.find("error") != std::string::npos)
      return;
    log::warning("run_pipeline: Slurm job " + id + " of an earlier run is still " + state +
                 " for this task; cancelling it first");
    run({"scancel", id});
    for (int pass = 0; pass < 60 && !final_states.count(state) && !state.empty(); ++pass)
    {
      sleep_for(1.0);
      state = state_of();
    }
  }

  void SlurmExecutor::start(const Launch &l)
  {
    cancel_earlier_job(l.work_prefix);
    const std::string script = l.work_prefix + ".sbatch";
    const std::string exit_file = l.work_prefix + ".exit";
    fs::remove(exit_file);
    {
      AtomicFile f(script);
      f.stream() << "#!/bin/sh\n# run_pipeline task " << l.name
                 << ": its Slurm job script (generated; the command is in the .command.txt "
                    "beside it).\n# The exit status goes to "
                 << exit_file << " for run_pipeline.\n";
      for (const auto &w : l.words)
        f.stream() << shell_quote(w) << ' ';
      f.stream() << "\nrc=$?\necho \"$rc\" > " << shell_quote(exit_file + ".tmp") << " && mv -f "
                 << shell_quote(exit_file + ".tmp") << ' ' << shell_quote(exit_file)
                 << "\nexit $rc\n";
      f.commit();
    }
    fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add);
    const int minutes = time_limit_minutes(l.expected_seconds);
    std::vector<std::string> words = {"sbatch",
                                      "--parsable",
                                      "--job-name=cj:" + l.name,
                                      "--output=" + l.log_path,
                                      "--open-mode=append",
                                      "--ntasks=" + std::to_string(std::max(1, l.ranks)),
                                      "--time=" + std::to_string(minutes),
                                      "--chdir=" + fs::current_path().string()};
    if (settings_.partition)
      words.push_back("--partition=" + *settings_.partition);
    if (settings_.account)
      words.push_back("--account=" + *settings_.account);
    if (settings_.qos)
      words.push_back("--qos=" + *settings_.qos);
    words.insert(words.end(), settings_.sbatch_args.begin(), settings_.sbatch_args.end());
    words.push_back(script);
    const CommandResult r = run(words);
    // --parsable prints "jobid" or "jobid;cluster".
    const std::string out = trimmed(r.output);
    const std::string id = out.substr(0, out.find(';'));
    if (r.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      throw NumericalError(
        "sbatch could not submit task " + l.name +
        (r.timed_out ? " (no answer within " + std::to_string(int(settings_.command_timeout)) +
                         " s, executor.command_timeout)"
                     : r.start_error.empty() ? " (exit " + std::to_string(r.exit_code) + ")"
                                             : " (" + r.start_error + ")") +
        ": " + out.substr(0, 1000));
    jobs_running_[id] = Job{l.node, l.name, l.work_prefix, l.log_path, exit_file, minutes};
    write_file_atomically(l.work_prefix + ".job.json",
                          "{\"kind\": \"slurm\", \"job_id\": \"" + id + "\", \"task\": " +
                            nlohmann::json(l.name).dump() + "}\n");
    log::info("  submitted " + l.name + " as Slurm job " + id + " (" +
              std::to_string(std::max(1, l.ranks)) + " tasks, time limit " +
              std::to_string(minutes) + " min)");
  }

  std::optional<std::map<std::string, std::string>> SlurmExecutor::query_states()
  {
    std::string ids;
    for (const auto &[id, job] : jobs_running_)
      ids += (ids.empty() ? "" : ",") + id;
    const CommandResult r =
      run({"squeue", "--noheader", "--states=all", "--format=%i|%T|%r", "--jobs=" + ids});
    // All the ids unknown (purged): squeue exits 1 with "Invalid job id"; that is an answer.
    if (r.exit_code != 0 && !(r.exit_code == 1 && r.output.find("Invalid job id") != std::string::npos))
    {
      ++failed_queries_;
      log::warning("run_pipeline: squeue " +
                   (r.timed_out ? std::string("did not answer") : "failed") + " (" +
                   std::to_string(failed_queries_) + " in a row): " +
                   trimmed(r.output.substr(0, 300)));
      return std::nullopt;
    }
    failed_queries_ = 0;
    std::map<std::string, std::string> states;
    std::istringstream lines(r.output);
    for (std::string line; std::getline(lines, line);)
      if (const auto bar = line.find('|'), bar2 = line.find('|', bar + 1);
          bar != std::string::npos && bar2 != std::string::npos)
      {
        std::string state = trimmed(line.substr(bar + 1, bar2 - bar - 1));
        // A job the node could not start is requeued and held until an administrator
        // releases it: it would never end. Report it (and cancel it) instead of waiting.
        if (state == "PENDING" && line.find("launch failed", bar2) != std::string::npos)
          state = launch_failed;
        states[trimmed(line.substr(0, bar))] = state;
      }
    return states;
  }

  Ended SlurmExecutor::ended(const std::string &id, const Job &job, const std::string &state)
  {
    if (state == launch_failed)
      run({"scancel", id});
    Ended e;
    e.node = job.node;
    e.record = {{"kind", "slurm"}, {"job_id", id}, {"state", state}};
    const auto code = read_exit_file(job.exit_file);
    fs::remove(job.exit_file);
    e.succeeded = state == "COMPLETED" && code.value_or(0) == 0;
    e.exit_status = code;
    // The scheduler ended it (TIMEOUT, CANCELLED, NODE_FAIL, PREEMPTED, OUT_OF_MEMORY, ...):
    // not the stage's own failure, which is COMPLETED or FAILED with its exit status.
    e.ended_from_outside = state != "COMPLETED" && state != "FAILED";
    e.what = "Slurm job " + id + " ended " + state +
             (code ? ", exit status " + std::to_string(*code) : std::string()) +
             (state == "TIMEOUT" ? ", time limit " + std::to_string(job.time_limit_min) + " min"
                                 : std::string()) +
             what_state_means(state);
    if (e.succeeded)  // the job id goes into the task's stamp; a failed job's files stay
    {
      fs::remove(job.prefix + ".job.json");
      fs::remove(job.prefix + ".sbatch");
    }
    return e;
  }

  Ended SlurmExecutor::forgotten(const std::string &id, const Job &job)
  {
    // The controller forgets a job MinJobAge (300 s by default) after it ends; the exit file
    // and the accounting database still know.
    if (const auto code = read_exit_file(job.exit_file))
      return ended(id, job, *code == 0 ? "COMPLETED" : "FAILED");
    const CommandResult r = run({"sacct", "--noheader", "--parsable2",
                                 "--format=JobID,State", "--jobs=" + id});
    std::istringstream lines(r.output);
    for (std::string line; r.exit_code == 0 && std::getline(lines, line);)
      if (line.rfind(id + "|", 0) == 0)
      {
        std::string state = trimmed(line.substr(id.size() + 1));
        state = state.substr(0, state.find(' '));  // "CANCELLED by 0" → CANCELLED
        if (final_states.count(state))
          return ended(id, job, state);
      }
    return ended(id, job, "UNKNOWN");
  }

  std::vector<Ended> SlurmExecutor::wait_any()
  {
    if (!sleep_for(settings_.poll_interval))
      return {};  // a signal: the scheduler looks at the interrupt flag
    const auto states = query_states();
    if (!states)
    {
      if (failed_queries_ >= 5)
        throw NumericalError("run_pipeline: the Slurm controller did not answer squeue " +
                             std::to_string(failed_queries_) + " times in a row (every " +
                             std::to_string(int(settings_.poll_interval)) +
                             " s, executor.poll_interval); its jobs are being cancelled");
      return {};
    }
    std::vector<Ended> done;
    for (auto it = jobs_running_.begin(); it != jobs_running_.end();)
    {
      const auto s = states->find(it->first);
      std::optional<Ended> e;
      if (s != states->end())
      {
        it->second.polls_missing = 0;
        if (final_states.count(s->second))
          e = ended(it->first, it->second, s->second);
      }
      else if (++it->second.polls_missing >= 2)  // not listed twice: purged, not just racing
        e = forgotten(it->first, it->second);
      if (e)
      {
        done.push_back(*e);
        it = jobs_running_.erase(it);
      }
      else
        ++it;
    }
    return done;
  }

  std::vector<int> SlurmExecutor::stop_all()
  {
    std::vector<int> stopped;
    if (jobs_running_.empty())
      return stopped;
    std::vector<std::string> words = {"scancel"};
    std::string ids;
    for (const auto &[id, job] : jobs_running_)
    {
      words.push_back(id);
      ids += (ids.empty() ? "" : " ") + id;
      stopped.push_back(job.node);
    }
    log::info("run_pipeline: cancelling Slurm jobs " + ids);
    const CommandResult r = run(words);
    if (r.exit_code != 0)
      log::error("run_pipeline: scancel " + ids + " failed (" + trimmed(r.output) +
                 "); cancel them yourself");
    // Wait (a few seconds, bounded) for the jobs to end, so that the next run does not find
    // a job still writing into a task's .partial folder.
    for (int pass = 0; pass < 30 && r.exit_code == 0; ++pass)
    {
      const auto states = query_states();
      if (!states)
        break;  // the controller does not answer: waiting longer would not tell us more
      bool all_ended = true;
      for (const auto &[id, job] : jobs_running_)
        if (states->count(id) && !final_states.count(states->at(id)))
          all_ended = false;
      if (all_ended)
        break;
      sleep_for(1.0);
    }
    jobs_running_.clear();
    return stopped;
  }
} // namespace clearjoint::pipeline
