// A single-node Slurm cluster for the tests of the Slurm executor (issue 33): munged,
// slurmctld and slurmd started as root with a generated slurm.conf (this machine's name and
// CPUs, proctrack/linuxproc, task/none, select/cons_tres, free ports), their pid files, logs,
// state, spool and the munge key in the cluster's folder /tmp/cj-slurm-<test pid> (short:
// slurmstepd's and munge's socket paths there must stay under 108 bytes); SLURM_CONF set for
// this process and its children. Stopped by their pids (jobs cancelled first); the clusters of
// a test that was killed (a ctest timeout) are stopped by the next one. No network beyond
// localhost.
// Every wait is bounded and says what it waited for when it gives up. On a loaded machine a
// daemon may write its pid file late (an empty file is not read as pid 0), and a stopped
// daemon or a job's slurmstepd may take seconds to go: stop() waits for the process to be gone
// (also after SIGKILL), the destructor for the cluster's slurmstepd, and a new cluster for the
// daemons of a finished test's cluster before it starts its own (never those of a test still
// running: another ctest may run its own cluster).
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
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace local_slurm
{
  namespace fs = std::filesystem;
  namespace test_support = clearjoint::test_support;

  /// `n` different TCP ports nobody listens on now (the kernel's picks). All are held until the
  /// last is picked: two picks one after the other may return the same port once the first
  /// socket is closed.
  inline std::vector<int> free_ports(const int n)
  {
    std::vector<int> fds, ports;
    for (int i = 0; i < n; ++i)
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
        fds.push_back(fd);
      ports.push_back(port);
    }
    for (const int fd : fds)
      ::close(fd);
    return ports;
  }

  /// A TCP port nobody listens on now (the kernel's pick).
  inline int free_port() { return free_ports(1).front(); }

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

  /// The name of process `pid` (/proc/<pid>/comm), "" if it is gone or a zombie (exited, not
  /// yet reaped: it holds no port or file any more).
  inline std::string live_process_name(const pid_t pid)
  {
    const std::string proc = "/proc/" + std::to_string(pid);
    const std::string stat = test_support::read_text(proc + "/stat");
    const auto paren = stat.rfind(')');
    if (stat.empty() || paren == std::string::npos || stat.compare(paren + 1, 3, " Z ") == 0)
      return "";
    std::string name = test_support::read_text(proc + "/comm");
    while (!name.empty() && name.back() == '\n')
      name.pop_back();
    return name;
  }

  /// A daemon of a test cluster: munged, slurmctld (and its slurmscriptd), slurmd, or a job's
  /// slurmstepd.
  struct Daemon
  {
    pid_t pid;
    std::string name;
    std::string folder;  ///< its cluster's folder, /tmp/cj-slurm-<pid of the test>
    pid_t owner() const { return std::atoi(folder.c_str() + 14); }
  };

  /// Every live daemon of every test cluster on this machine. munged, slurmctld and slurmd name
  /// the folder on their command line; slurmscriptd and slurmstepd have it in SLURM_CONF, which
  /// the test sets before it starts the daemons.
  inline std::vector<Daemon> cluster_daemons()
  {
    std::vector<Daemon> found;
    std::error_code ec;
    for (fs::directory_iterator it("/proc", ec), end; !ec && it != end; it.increment(ec))
    {
      const std::string entry = it->path().filename().string();
      if (entry.find_first_not_of("0123456789") != std::string::npos)
        continue;
      const pid_t pid = std::atoi(entry.c_str());
      const std::string name = live_process_name(pid);
      if (name != "munged" && name != "slurmctld" && name != "slurmscriptd" &&
          name != "slurmd" && name != "slurmstepd")
        continue;
      const std::string text = test_support::read_text(it->path() / "cmdline") + '\n' +
                               test_support::read_text(it->path() / "environ");
      const auto at = text.find("/tmp/cj-slurm-");
      if (at == std::string::npos)
        continue;  // a Slurm or munge of the machine's own, not ours
      const auto end_of_pid = text.find_first_not_of("0123456789", at + 14);
      found.push_back({pid, name, text.substr(at, end_of_pid - at)});
    }
    return found;
  }

  inline std::string describe(const std::vector<Daemon> &daemons)
  {
    std::string text;
    for (const auto &d : daemons)
      text += (text.empty() ? "" : ", ") + d.name + " " + std::to_string(d.pid) + " of " + d.folder;
    return text;
  }

  /// Waits (at most `seconds`) until `which` (re-evaluated each time) finds no daemon; returns
  /// those still there. A wait is said on stderr (what for, how long): the test's output then
  /// shows what a flaky start had found.
  template <typename Which>
  std::vector<Daemon> wait_until_gone(Which which, const double seconds, const std::string &what)
  {
    std::vector<Daemon> left = which();
    if (left.empty())
      return left;
    const std::string first = describe(left);
    const auto started = std::chrono::steady_clock::now();
    for (int i = 0; i < int(seconds * 10) && !left.empty(); ++i)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      left = which();
    }
    std::cerr << "local_slurm: waited "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()
              << " s for " << what << " (" << first << ")"
              << (left.empty() ? ": gone\n" : ": still there\n");
    return left;
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
      if (!wait_for_finished_clusters())
        return;
      fs::create_directories(dir_ + "/state");
      fs::create_directories(dir_ + "/spool");
      write_key();
      host_ = short_hostname();
      const long cpus = ::sysconf(_SC_NPROCESSORS_ONLN);
      const std::vector<int> ports = free_ports(2);
      std::ofstream(dir_ + "/slurm.conf")
        << "# the test's single-node cluster (tests/unit/pipeline/local_slurm.h)\n"
        << "ClusterName=clearjoint_test\nSlurmctldHost=" << host_ << "(127.0.0.1)\n"
        << "SlurmUser=root\nSlurmdUser=root\n"
        << "SlurmctldPort=" << ports[0] << "\nSlurmdPort=" << ports[1] << "\n"
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
      // The node registers within seconds; 60 s is the most we wait. "idle" itself: "idle*"
      // is a node the controller does not hear from (slurmd not registered, or gone).
      std::string state;
      for (int i = 0; i < 300; ++i)
      {
        state = command_output("sinfo --noheader --format=%T --nodes=" + host_);
        state = state.substr(0, state.find_first_of(" \n"));
        if (state == "idle")
          return;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
      failure = "the node did not become idle within 60 s (sinfo: '" + state + "'); slurmd.log: " +
                    test_support::read_text(dir_ + "/slurmd.log").substr(0, 2000) +
                    "\nslurmctld.log: " +
                    test_support::read_text(dir_ + "/slurmctld.log").substr(0, 2000);
    }

    ~Cluster()
    {
      if (!pids_.empty())
      {
        // No job outlives the test: cancel all, wait (at most 20 s) for the queue to empty.
        std::system("scancel --full --quiet --user=root > /dev/null 2>&1");
        const auto queue_now = []() {
          return command_output("squeue --noheader --format='%i %T'");
        };
        std::string queue = queue_now();
        for (int i = 0; i < 100 && !queue.empty(); ++i)
        {
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
          queue = queue_now();
        }
        if (!queue.empty())
          std::cerr << "local_slurm: jobs still in the queue 20 s after scancel: " << queue;
      }
      for (auto it = pids_.rbegin(); it != pids_.rend(); ++it)  // slurmd, slurmctld, munged
        stop(*it);
      // A job's slurmstepd outlives slurmd while it ends the job's processes (KillWait=5 s):
      // the next test's cluster starts on a machine without it.
      const auto own = [this]() {
        std::vector<Daemon> mine;
        for (const auto &d : cluster_daemons())
          if (d.folder == dir_)
            mine.push_back(d);
        return mine;
      };
      if (!pids_.empty())
        for (const auto &d : wait_until_gone(own, 20.0, "the daemons of this test's cluster"))
        {
          std::cerr << "local_slurm: " << describe({d}) << " still there 20 s after the "
                    << "daemons stopped; stopping it\n";
          stop(d.pid);
        }
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

    /// Waits (at most 30 s) until no daemon of another test's cluster whose test has ended is
    /// left (a cluster still going down: a slurmstepd ending its job, a daemon not yet gone),
    /// then stops what is left; false (and `failure`) if something survives SIGKILL.
    bool wait_for_finished_clusters()
    {
      const auto finished = []() {
        std::vector<Daemon> left;
        for (const auto &d : cluster_daemons())
          if (d.owner() != ::getpid() && live_process_name(d.owner()).empty())
            left.push_back(d);
        return left;
      };
      const std::vector<Daemon> left =
        wait_until_gone(finished, 30.0, "the daemons of a finished test's cluster");
      if (left.empty())
        return true;
      std::cerr << "local_slurm: stopping daemons of finished tests still there after 30 s: "
                << describe(left) << "\n";
      for (const auto &d : left)
        stop(d.pid);
      const std::vector<Daemon> survivors = finished();
      if (!survivors.empty())
        failure = "daemons of an earlier test's cluster do not go (SIGTERM, SIGKILL): " +
                  describe(survivors);
      return survivors.empty();
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

    /// Runs a daemon (it forks into the background) and waits (at most 30 s; ~20 ms on a quiet
    /// machine) until its pid file names a live process of that name. The daemon creates the
    /// file before it writes its pid: an empty file is waited for, not read as pid 0.
    bool start(const std::string &command, const std::string &name)
    {
      const std::string log = dir_ + "/" + name + ".start.log";
      const int rc = test_support::run_command(command, log);
      const std::string pid_file = dir_ + "/" + name + ".pid";
      pid_t pid = 0;
      int waits = 0;
      for (; waits < 300 && rc == 0; ++waits)
      {
        pid = std::atoi(test_support::read_text(pid_file).c_str());
        if (pid > 0 && live_process_name(pid) == name)
          break;
        pid = 0;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      if (waits > 0 && pid > 0)
        std::cerr << "local_slurm: " << name << "'s pid file named a live " << name << " after "
                  << waits * 0.1 << " s\n";
      if (rc != 0 || pid <= 0)
      {
        failure = name + (rc != 0 ? " did not start (exit " + std::to_string(rc) + "): "
                                  : " did not start: no live " + name + " in " + pid_file +
                                      " within 30 s (pid file: '" +
                                      test_support::read_text(pid_file) + "'): ") +
                  test_support::read_text(log) +
                  test_support::read_text(dir_ + "/" + name + ".log").substr(0, 2000);
        return false;
      }
      pids_.push_back(pid);
      return true;
    }

    /// SIGTERM, up to 10 s to exit, then SIGKILL and up to 5 s more until it is gone (a
    /// process being killed still holds its ports and files for a moment). Only while the pid
    /// still names the same daemon (not a process that got the pid since).
    static void stop(const pid_t pid)
    {
      const std::string name = live_process_name(pid);
      if (name.empty())
        return;
      const auto same = [&]() { return live_process_name(pid) == name; };
      ::kill(pid, SIGTERM);
      for (int i = 0; i < 100 && same(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!same())
        return;
      ::kill(pid, SIGKILL);
      for (int i = 0; i < 50 && same(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (same())
        std::cerr << "local_slurm: " << name << " " << pid << " still there 5 s after SIGKILL\n";
    }

    std::string dir_, host_;
    std::vector<pid_t> pids_;
  };
} // namespace local_slurm
