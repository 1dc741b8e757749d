// Output files. Every file clearjoint writes goes through OutputFile (or AtomicFile, which
// adds the temporary name): its stream remembers the OS error (errno) of the first write that
// failed, so a full disk or an I/O error ends the stage with WriteError ("cannot write
// '<path>': No space left on device"), one line, instead of a stream that silently went bad.
//
// Atomic file writes: write to "<path>.tmp.<pid>", then rename over <path> on commit().
// A run killed halfway leaves at most a *.tmp.* file, never a file that looks complete.
#pragma once

#include "common/interrupt.h"

#include <functional>
#include <memory>
#include <ostream>
#include <string>

namespace clearjoint
{
  namespace detail
  {
    class FdBuf;
  }

  /// A file written through a buffered std::ostream over a POSIX descriptor.
  class OutputFile
  {
  public:
    /// Creates (truncates) `path`. A folder that does not exist or is not writable is an
    /// InputError naming the file; a full disk or an I/O error is a WriteError.
    explicit OutputFile(const std::string &path);
    /// Closes the file; errors are not reported here (call close()).
    ~OutputFile();
    OutputFile(const OutputFile &) = delete;
    OutputFile &operator=(const OutputFile &) = delete;

    std::ostream &stream() { return *out_; }
    /// Throws WriteError if a write has failed so far (cheap: call it after each record).
    void check() const;
    /// Flushes and closes; throws WriteError naming the file and the OS reason.
    void close();
    const std::string &path() const { return path_; }

  private:
    std::string path_;
    std::unique_ptr<detail::FdBuf> buf_;
    std::unique_ptr<std::ostream> out_;
  };

  /// Writes `path` with `write` (e.g. a library's writer taking an std::ostream). If a write
  /// fails, WriteError naming `path` and the OS reason is thrown, also when `write` itself
  /// threw on the failed stream (deal.II's ExcIO and its stack trace are replaced).
  void write_file(const std::string &path, const std::function<void(std::ostream &)> &write);

  class AtomicFile
  {
  public:
    /// Opens the temporary file; throws InputError naming `path` if it cannot be created
    /// (e.g. the directory does not exist or is not writable), WriteError on a full disk.
    explicit AtomicFile(const std::string &path);
    /// Removes the temporary file if commit() was not called.
    ~AtomicFile();
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    std::ostream &stream() { return file_->stream(); }
    /// Throws WriteError (naming the final path) if a write has failed so far.
    void check() const;
    /// Flushes, checks the stream, renames into place. Throws WriteError on failure.
    void commit();

    const std::string &path() const { return path_; }

  private:
    std::string path_, tmp_path_;
    std::unique_ptr<OutputFile> file_;
    interrupt::Temporary temporary_;  ///< removed by a hard stop (common/interrupt.h)
    bool committed_ = false;
  };

  /// Writes `content` to `path` atomically.
  void write_file_atomically(const std::string &path, const std::string &content);

  /// Reads a whole file; throws InputError naming the file if it cannot be read.
  std::string read_file(const std::string &path);
} // namespace clearjoint
