#include "common/manifest.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "common/sha256.h"
#include "common/strict_reader.h"

#include <openssl/opensslv.h>

#include <ctime>
#include <filesystem>

namespace clearjoint
{
  namespace
  {
    std::string utc_now()
    {
      std::time_t t = std::time(nullptr);
      char buf[32];
      std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
      return buf;
    }
  } // namespace

  nlohmann::json common_library_versions()
  {
    nlohmann::json v;
    v["nlohmann_json"] = std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                         std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                         std::to_string(NLOHMANN_JSON_VERSION_PATCH);
    v["openssl"] = OPENSSL_VERSION_TEXT;
    return v;
  }

  Manifest::Manifest(std::string stage, std::string manifest_path, const int argc,
                     const char *const *argv)
    : stage_(std::move(stage))
    , path_(std::move(manifest_path))
    , libraries_(common_library_versions())
    , start_(std::chrono::steady_clock::now())
    , started_utc_(utc_now())
  {
    for (int i = 0; i < argc && argv; ++i)
      command_line_.emplace_back(argv[i]);
  }

  Manifest::~Manifest()
  {
    if (!written_)
    {
      try
      {
        write("failed", "the stage ended before it recorded a result");
      }
      catch (...)
      {
        // Destructors must not throw; the missing manifest is itself the signal.
      }
    }
  }

  void Manifest::add_input(const std::string &path)
  {
    std::string hash;
    try
    {
      hash = sha256_file(path);
    }
    catch (...)
    {
      hash = "unreadable";
    }
    inputs_.emplace_back(path, hash);
  }

  void Manifest::add_output(const std::string &path) { outputs_.push_back(path); }

  void Manifest::set_library_version(const std::string &name, const std::string &version)
  {
    libraries_[name] = version;
  }

  double Manifest::elapsed_seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  void Manifest::write(const std::string &status, const std::string &message)
  {
    nlohmann::json j;
    j["schema"] = "clearjoint.manifest/1";
    j["stage"] = stage_;
    j["status"] = status;
    j["message"] = message;
    j["command_line"] = command_line_;
    j["clearjoint_version"] = clearjoint_version;
    j["started_utc"] = started_utc_;
    j["inputs"] = nlohmann::json::array();
    for (const auto &[p, h] : inputs_)
      j["inputs"].push_back({{"path", p}, {"sha256", h}});
    j["outputs"] = nlohmann::json::array();
    for (const auto &p : outputs_)
    {
      nlohmann::json o = {{"path", p}};
      if (std::filesystem::is_regular_file(p))
        o["sha256"] = sha256_file(p);
      else
        o["sha256"] = nullptr;  // directories, or outputs not written because the stage failed
      j["outputs"].push_back(o);
    }
    j["libraries"] = libraries_;
    j["wall_time"] = {{"value", elapsed_seconds()}, {"unit", "s"}};
    j["warnings"] = log::n_warnings();
    j["extra"] = extra_;
    // replace: a path given on the command line need not be UTF-8 (a byte 0xFF in a folder
    // name); the manifest must still be written rather than the process aborted.
    const auto text = j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    write_file_atomically(path_, text + "\n");
    written_ = true;
  }

  void create_work_folder(const std::string &work, const std::string &dir)
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::remove_all(work, ec);
    ec.clear();
    if (!fs::create_directories(work, ec) || ec)
      throw InputError("", "--output", dir, "a directory that can be created",
                       "cannot create " + work + ": " +
                         (ec ? ec.message() : std::string("it already exists")));
  }

  void check_output_replaceable(const std::string &dir, const std::string &stage)
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(dir, ec))
      return;
    bool ours = fs::is_directory(dir, ec) && fs::is_empty(dir, ec);
    if (!ours && fs::is_regular_file(dir + "/manifest.json", ec))
    {
      try
      {
        ours = read_json_file(dir + "/manifest.json").value("stage", "") == stage;
      }
      catch (const std::exception &)
      {
        ours = false;
      }
    }
    if (!ours)
      throw InputError("", "--output", dir, "a new directory, an empty one, or a previous " +
                                              stage + " output",
                       "it exists and does not look like an " + stage +
                         " output; nothing was changed");
  }
} // namespace clearjoint
