// manifest.json: what a stage did, from what, with what, and whether it finished.
//
//   { "schema": "clearjoint.manifest/1", "stage": "fit_stage", "status": "complete",
//     "message": "", "command_line": [...], "clearjoint_version": "0.1.0",
//     "inputs":  [ {"path": ..., "sha256": ...} ], "outputs": [ {"path": ..., "sha256": ...} ],
//     "libraries": {"ceres": "2.1.0", ...}, "wall_time": {"value": 1.2, "unit": "s"},
//     "started_utc": "...", "extra": {...} }
//
// The destructor writes the manifest with status "failed" if write() was never called, so a
// stage that dies by exception still leaves an honest record.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <string>
#include <vector>

namespace clearjoint
{
  inline constexpr const char *clearjoint_version = "0.1.0";

  class Manifest
  {
  public:
    /// manifest_path: where manifest.json goes (its directory must exist when written).
    Manifest(std::string stage, std::string manifest_path, int argc = 0,
             const char *const *argv = nullptr);
    ~Manifest();

    /// Records an input with its sha256 (a file that cannot be read gets sha256 "unreadable").
    void add_input(const std::string &path);
    /// Records an output; its sha256 is computed when the manifest is written.
    void add_output(const std::string &path);
    void set_library_version(const std::string &name, const std::string &version);
    /// Free-form stage results (e.g. the law's K and n) stored under "extra".
    nlohmann::json &extra() { return extra_; }

    /// status: "complete", "incomplete" or "failed"; message: why (empty if complete).
    void write(const std::string &status, const std::string &message = "");
    bool written() const { return written_; }
    /// No manifest at all (the destructor writes none): for an input error or an interrupt
    /// that leaves nothing behind.
    void discard() { written_ = true; }

    double elapsed_seconds() const;

  private:
    std::string stage_, path_;
    std::vector<std::string> command_line_;
    std::vector<std::pair<std::string, std::string>> inputs_;
    std::vector<std::string> outputs_;
    nlohmann::json libraries_ = nlohmann::json::object();
    nlohmann::json extra_ = nlohmann::json::object();
    std::chrono::steady_clock::time_point start_;
    std::string started_utc_;
    bool written_ = false;
  };

  /// Versions of the libraries every stage links (yaml-cpp, nlohmann-json, OpenSSL).
  nlohmann::json common_library_versions();

  /// A stage replaces an existing output folder `dir` only if it is empty or holds an earlier
  /// output of the same `stage` (its manifest.json says so): never delete a folder the stage
  /// did not write. Throws InputError naming --output otherwise.
  void check_output_replaceable(const std::string &dir, const std::string &stage);

  /// Creates `work` (the temporary folder DIR.tmp.<pid> a stage writes before renaming it to
  /// `dir`), and the folders above it, after removing a stale one. InputError naming --output if
  /// it cannot be made (a file in the way, no permission) — not an "unexpected failure".
  void create_work_folder(const std::string &work, const std::string &dir);
} // namespace clearjoint
