// Error types shared by every stage and the exit codes their main() returns.
//  - InputError: something the user gave us is wrong; the message names the file, the key path,
//    the value and the allowed range, so the user can fix it without reading code.
//  - NumericalError: a solver did not converge or produced a non-finite value.
#pragma once

#include <stdexcept>
#include <string>

namespace clearjoint
{
  /// Process exit codes documented in every stage's --help.
  enum ExitCode : int
  {
    exit_success         = 0,
    exit_input_error     = 1,
    exit_numerical_error = 2,
  };

  class InputError : public std::runtime_error
  {
  public:
    /// file: the input file (may be empty for command-line input); key_path: e.g.
    /// "geometry.t_B"; value: the offending value as text; allowed: e.g. "> 0 m" or
    /// "one of error|clamp|extend"; detail: optional free text.
    InputError(std::string file, std::string key_path, std::string value,
               std::string allowed, std::string detail = "");

    /// A plain message, for errors that have no single key (e.g. a malformed file).
    explicit InputError(const std::string &message);

    const std::string &file() const { return file_; }
    const std::string &key_path() const { return key_path_; }

  private:
    std::string file_, key_path_;
  };

  class NumericalError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Formats a double for messages with enough digits to be unambiguous ("%.6g").
  std::string format_value(double value);
} // namespace clearjoint
