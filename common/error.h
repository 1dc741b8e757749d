// Error types shared by every stage and the exit codes their main() returns.
//  - InputError: something the user gave us is wrong; the message names the file, the key path,
//    the value and the allowed range, so the user can fix it without reading code.
//  - NumericalError: a solver did not converge or produced a non-finite value.
//  - WriteError: an output could not be written (a full disk, an I/O error, a read-only file
//    system); the message names the file and the OS reason (strerror) on one line.
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
    exit_write_error     = 3,  ///< an output could not be written (WriteError)
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

  class WriteError : public std::runtime_error
  {
  public:
    /// "cannot write '<path>': <strerror(os_error)>".
    WriteError(const std::string &path, int os_error);
    /// "cannot write '<path>': <reason>".
    WriteError(const std::string &path, const std::string &reason);

    const std::string &path() const { return path_; }
    const std::string &reason() const { return reason_; }

  private:
    std::string path_, reason_;
  };

  /// True for the errno values of a failed write or create that are not the user's input (a
  /// full disk, a quota, an I/O error, a read-only file system, a file too large).
  bool is_write_failure(int os_error);

  /// Formats a double for messages with enough digits to be unambiguous ("%.6g").
  std::string format_value(double value);
} // namespace clearjoint
