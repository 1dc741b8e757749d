#include "fe_stage/results/collective_write.h"

#include "common/error.h"
#include "common/interrupt.h"

#include <exception>
#include <string>

namespace clearjoint::fe
{
  namespace
  {
    void broadcast(std::string &text, const int from, MPI_Comm comm)
    {
      unsigned long n = text.size();
      MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, from, comm);
      text.resize(n);
      if (n > 0)
        MPI_Bcast(text.data(), int(n), MPI_CHAR, from, comm);
    }
    bool together = false;

    /// The exit code fe_stage's main() gives the exception that `e` holds.
    int exit_code_of(const std::exception_ptr &e)
    {
      try
        {
          std::rethrow_exception(e);
        }
      catch (const InputError &)
        {
          return exit_input_error;
        }
      catch (const interrupt::Interrupted &)
        {
          return interrupt::exit_code();
        }
      catch (...)
        {
          return exit_numerical_error;
        }
    }
  }  // namespace

  StoppedElsewhere::StoppedElsewhere(const int exit_code)
    : std::runtime_error("stopped: another MPI rank failed")
    , code_(exit_code)
  {}

  bool failed_together() { return together; }

  void write_collectively(MPI_Comm comm, const std::function<void()> &write)
  {
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    if (n_ranks == 1)
      {
        write();
        return;
      }
    std::string path, reason;
    std::exception_ptr failure;
    int kind = 0;  // 1 WriteError, 2 anything else
    try
      {
        write();
      }
    catch (const WriteError &e)
      {
        failure = std::current_exception();
        kind = 1;
        path = e.path();
        reason = e.reason();
      }
    catch (...)
      {
        failure = std::current_exception();
        kind = 2;
      }
    int first = failure ? rank : n_ranks, any = n_ranks;
    MPI_Allreduce(&first, &any, 1, MPI_INT, MPI_MIN, comm);
    if (any == n_ranks)
      return;
    together = true;
    int first_kind = kind, code = failure ? exit_code_of(failure) : 0;
    MPI_Bcast(&first_kind, 1, MPI_INT, any, comm);
    MPI_Bcast(&code, 1, MPI_INT, any, comm);
    if (first_kind == 1)
      {
        broadcast(path, any, comm);
        broadcast(reason, any, comm);
        throw WriteError(path, reason);
      }
    if (failure)
      std::rethrow_exception(failure);
    throw StoppedElsewhere(code);
  }
}  // namespace clearjoint::fe
