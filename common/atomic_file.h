// Atomic file writes: write to "<path>.tmp.<pid>", then rename over <path> on commit().
// A run killed halfway leaves at most a *.tmp.* file, never a file that looks complete.
#pragma once

#include <fstream>
#include <string>

namespace clearjoint
{
  class AtomicFile
  {
  public:
    /// Opens the temporary file; throws InputError naming `path` if it cannot be created
    /// (e.g. the directory does not exist or is not writable).
    explicit AtomicFile(const std::string &path);
    /// Removes the temporary file if commit() was not called.
    ~AtomicFile();
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    std::ofstream &stream() { return out_; }
    /// Flushes, checks the stream, renames into place. Throws std::runtime_error on failure.
    void commit();

    const std::string &path() const { return path_; }

  private:
    std::string path_, tmp_path_;
    std::ofstream out_;
    bool committed_ = false;
  };

  /// Writes `content` to `path` atomically.
  void write_file_atomically(const std::string &path, const std::string &content);

  /// Reads a whole file; throws InputError naming the file if it cannot be read.
  std::string read_file(const std::string &path);
} // namespace clearjoint
