// The error handling every stage's main() shares (STYLE.md: parse → construct → run, inside
// try/catch): runs the body and turns what escapes it into a logged message and an exit code.
#pragma once

#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"

#include <exception>
#include <string>

namespace clearjoint
{
  /// Returns body()'s exit code; InputError → 1, NumericalError → 2, WriteError (a full
  /// disk, an I/O error) → 3 with one line "<program>: cannot write '<file>': <reason>; ...",
  /// an interrupt (SIGINT, SIGTERM; common/interrupt.h) → 130/143, anything else → 2 with
  /// "unexpected failure" (a bug or a resource problem, reported as such).
  template <typename Body>
  int run_stage_main(const std::string &program, Body &&body)
  {
    try
    {
      return body();
    }
    catch (const WriteError &e)
    {
      log::error(program + ": " + e.what() +
                 "; nothing new written (temporary outputs removed, earlier outputs left as "
                 "they were)");
      return exit_write_error;
    }
    catch (const InputError &e)
    {
      log::error(e.what());
      return exit_input_error;
    }
    catch (const NumericalError &e)
    {
      log::error(e.what());
      return exit_numerical_error;
    }
    catch (const interrupt::Interrupted &e)
    {
      log::error(std::string(e.what()) +
                 "; temporary outputs removed, earlier outputs left as they were");
      return interrupt::exit_code();
    }
    catch (const std::exception &e)
    {
      log::error(std::string("unexpected failure: ") + e.what());
      return exit_numerical_error;
    }
  }
} // namespace clearjoint
