// A single-node Slurm cluster for the tests of the Slurm executor (issue 33): munged,
// slurmctld and slurmd started as root with a generated slurm.conf (this machine's name and
// CPUs, proctrack/linuxproc, task/none, select/cons_tres, free ports), their pid files, logs,
// state, spool and the munge key in the cluster's folder /tmp/cj-slurm-<test pid> (short:
// slurmstepd's and munge's socket paths there must stay under 108 bytes); SLURM_CONF set for
// this process and its children. Stopped by their pids (jobs cancelled first); the clusters of
// a test that was killed (a ctest timeout) are stopped by the next one. No network beyond
// localhost.
// `skip_reason` says why it cannot run here (not root, packages missing); `failure` why it did
// not start although it could (a daemon failing, the node never idle) — a test failure.
#pragma once

#include "test_support.h"

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace local_slurm
{
  namespace fs = std::filesystem;
  namespace test_support = clearjoint::test_support;

  /// A TCP port nobody listens on now (the kernel's pick).
  inline int free_port()
  {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof(a);
    int port = 0;
    if (fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr *>(&a), sizeof(a)) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr *>(&a), &len) == 0)
      port = ntohs(a.sin_port);
    if (fd >= 0)
      ::close(fd);
    return port;
  }

  inline std::string command_output(const std::string &command)
  {
    const std::string out = "/tmp/local_slurm_out_" + std::to_string(::getpid());
    test_support::run_command(command, out);
    const std::string text = test_support::read_text(out);
    fs::remove(out);
    return text;
  }

  inline bool on_path(const std::string &name)
  {
    return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
  }

  class Cluster
  {
  public:
    /// The folder of this process's cluster.
    static std::string folder() { return "/tmp/cj-slurm-" + std::to_string(::getpid()); }

    Cluster()
      : dir_(folder())
    {
      if (::geteuid() != 0)
      {
        skip_reason = "not root: slurmctld and slurmd of the test cluster run as root";
        return;
      }
      for (const std::string c : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel",
                                  "sinfo"})
        if (!on_path(c) && !fs::exists("/usr/sbin/" + c))
        {
          skip_reason = c + " not installed (Debian packages slurm-wlm, munge: scripts/setup)";
          return;
        }
      stop_stale_clusters();
      fs::create_directories(dir_ + "/state");
      fs::create_directories(dir_ + "/spool");
      write_key();
      host_ = short_hostname();
      const long cpus = ::sysconf(_SC_NPROCESSORS_ONLN);
      std::ofstream(dir_ + "/slurm.conf")
        << "# the test's single-node cluster (tests/unit/pipeline/local_slurm.h)\n"
        << "ClusterName=clearjoint_test\nSlurmctldHost=" << host_ << "(127.0.0.1)\n"
        << "SlurmUser=root\nSlurmdUser=root\n"
        << "SlurmctldPort=" << free_port() << "\nSlurmdPort=" << free_port() << "\n"
        << "AuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket=" << dir_ << "/munge.socket\n"
        << "StateSaveLocation=" << dir_ << "/state\nSlurmdSpoolDir=" << dir_ << "/spool\n"
        << "SlurmctldPidFile=" << dir_ << "/slurmctld.pid\nSlurmdPidFile=" << dir_ << "/slurmd.pid\n"
        << "SlurmctldLogFile=" << dir_ << "/slurmctld.log\nSlurmdLogFile=" << dir_ << "/slurmd.log\n"
        << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
        << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
        << "SchedulerType=sched/backfill\nMpiDefault=none\nReturnToService=2\n"
        << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
        << "JobCompType=jobcomp/none\nKillWait=5\nMinJobAge=300\n"
        << "NodeName=" << host_ << " NodeAddr=127.0.0.1 CPUs=" << cpus << " State=UNKNOWN\n"
        << "PartitionName=test Nodes=" << host_ << " Default=YES MaxTime=INFINITE State=UP\n";
      ::setenv("SLURM_CONF", (dir_ + "/slurm.conf").c_str(), 1);
      const std::string conf = dir_ + "/slurm.conf";
      if (!start("munged -f --key-file=" + dir_ + "/munge.key --socket=" + dir_ +
                   "/munge.socket --pid-file=" + dir_ + "/munged.pid --log-file=" + dir_ +
                   "/munged.log --seed-file=" + dir_ + "/munged.seed",
                 "munged") ||
          !start("slurmctld -f " + conf, "slurmctld") ||
          !start("slurmd -f " + conf + " -N " + host_, "slurmd"))
        return;
      // The node registers within seconds; 60 s is the most we wait.
      for (int i = 0; i < 300; ++i)
      {
        if (command_output("sinfo --noheader --format=%T --nodes=" + host_).find("idle") == 0)
          return;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
      failure = "the node did not become idle within 60 s; slurmd.log: " +
                    test_support::read_text(dir_ + "/slurmd.log").substr(0, 2000);
    }

    ~Cluster()
    {
      if (!pids_.empty())
      {
        // No job outlives the test: cancel all, wait (at most 20 s) for the queue to empty.
        std::system("scancel --full --quiet --user=root > /dev/null 2>&1");
        for (int i = 0; i < 100 && !command_output("squeue --noheader --format=%i").empty(); ++i)
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
      for (auto it = pids_.rbegin(); it != pids_.rend(); ++it)  // slurmd, slurmctld, munged
        stop(*it);
      ::unsetenv("SLURM_CONF");
      if (::geteuid() == 0)
        fs::remove_all(dir_);
    }

    std::string skip_reason;  ///< not empty: it cannot run here (skip the test)
    std::string failure;      ///< not empty: it could run but did not start (fail the test)
    const std::string &host() const { return host_; }
    std::string dir() const { return dir_; }

  private:
    /// Daemons of clusters whose test process is gone (killed at a ctest timeout, say).
    static void stop_stale_clusters()
    {
      for (const auto &e : fs::directory_iterator("/tmp"))
      {
        const std::string name = e.path().filename().string();
        if (name.rfind("cj-slurm-", 0) != 0 || fs::exists("/proc/" + name.substr(9)))
          continue;
        for (const std::string d : {"slurmd", "slurmctld", "munged"})
        {
          const pid_t pid = std::atoi(test_support::read_text(e.path() / (d + ".pid")).c_str());
          // only that daemon, not a process that got its pid since
          if (pid > 0 && test_support::read_text("/proc/" + std::to_string(pid) + "/comm")
                             .rfind(d.substr(0, 9), 0) == 0)
            stop(pid);
        }
        fs::remove_all(e.path());
      }
    }

    static std::string short_hostname()
    {
      char name[256] = {};
      ::gethostname(name, sizeof(name) - 1);
      const std::string h = name;
      return h.substr(0, h.find('.'));
    }

    void write_key()
    {
      std::random_device rd;
      std::string key(1024, '\0');
      for (auto &c : key)
        c = char(rd());
      const std::string path = dir_ + "/munge.key";
      std::ofstream(path, std::ios::binary) << key;
      fs::permissions(path, fs::perms::owner_read, fs::perm_options::replace);
    }

    /// Runs a daemon (it forks into the background) and reads its pid file.
    bool start(const std::string &command, const std::string &name)
    {
      const std::string log = dir_ + "/" + name + ".start.log";
      const int rc = test_support::run_command(command, log);
      const std::string pid_file = dir_ + "/" + name + ".pid";
      for (int i = 0; i < 50 && !fs::exists(pid_file); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      const pid_t pid = std::atoi(test_support::read_text(pid_file).c_str());
      if (rc != 0 || pid <= 0)
      {
        failure = name + " did not start (exit " + std::to_string(rc) + "): " +
                      test_support::read_text(log) +
                      test_support::read_text(dir_ + "/" + name + ".log").substr(0, 2000);
        return false;
      }
      pids_.push_back(pid);
      return true;
    }

    /// SIGTERM, up to 10 s to exit, then SIGKILL.
    static void stop(const pid_t pid)
    {
      ::kill(pid, SIGTERM);
      for (int i = 0; i < 100 && ::kill(pid, 0) == 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      ::kill(pid, SIGKILL);
    }

    std::string dir_, host_;
    std::vector<pid_t> pids_;
  };
} // namespace local_slurm
