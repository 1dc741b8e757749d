#include "pipeline/executor_config.h"

#include "common/error.h"

#include <thread>

namespace clearjoint::pipeline
{
  ExecutorConfig read_executor_config(StrictObject e)
  {
    ExecutorConfig c;
    c.kind = e.string("kind", {"local", "slurm"});
    if (c.kind == "local")
    {
      e.finish();  // the Slurm keys mean nothing here: an error, not silently ignored
      return c;
    }
    SlurmSettings &s = c.slurm;
    for (const auto &[key, field] : {std::pair{"partition", &s.partition},
                                     std::pair{"account", &s.account}, std::pair{"qos", &s.qos}})
      if (e.has(key))
      {
        *field = e.string(key);
        if (field->value().empty() || field->value().find_first_of(" \t\n,'\"") != std::string::npos)
          e.fail(key, field->value(), "a Slurm name without spaces, quotes or commas");
      }
      else
        e.allow(key);
    s.time_margin = e.number_or("time_margin", s.time_margin, Range::closed(1.0, 100.0));
    s.time_unmeasured =
      e.number_or("time_unmeasured", s.time_unmeasured, Range::closed(1.0, 525600.0, "min"));
    s.poll_interval = e.number_or("poll_interval", s.poll_interval, Range::closed(1.0, 600.0, "s"));
    s.command_timeout =
      e.number_or("command_timeout", s.command_timeout, Range::closed(1.0, 600.0, "s"));
    s.mpi_launcher = e.string_or("mpi_launcher", s.mpi_launcher, {"mpirun", "srun"});
    s.srun_mpi = e.string_or("srun_mpi", s.srun_mpi, {"pmix", "pmi2", "pmix_v3", "pmix_v4"});
    if (e.has("sbatch_args"))
    {
      const auto &args = e.raw("sbatch_args");
      if (!args.is_array())
        e.fail("sbatch_args", args.dump(), "a list of sbatch options, e.g. [\"--mem=4G\"]");
      for (const auto &a : args)
        if (!a.is_string() || a.get<std::string>().rfind("--", 0) != 0)
          e.fail("sbatch_args", a.dump(), "sbatch options starting with '--', e.g. \"--mem=4G\"");
        else
          s.sbatch_args.push_back(a.get<std::string>());
    }
    else
      e.allow("sbatch_args");
    e.finish();
    return c;
  }

  int machine_cores()
  {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : int(n);
  }

  int checked_jobs(const long jobs, const std::string &file, const std::string &key)
  {
    if (jobs < 1 || jobs > max_jobs)
      throw InputError(file, key, std::to_string(jobs),
                       "an integer in [1, " + std::to_string(max_jobs) + "]",
                       "tasks (local: CPU slots, a task on R MPI ranks takes R; slurm: jobs "
                       "queued at once); default: the machine's cores (" +
                         std::to_string(machine_cores()) + ")");
    return int(jobs);
  }
} // namespace clearjoint::pipeline
