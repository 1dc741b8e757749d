#include "fe_stage/solve/rolling_restart.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "fe_stage/results/collective_write.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <system_error>

namespace clearjoint::fe::detail
{
  namespace
  {
    namespace fs = std::filesystem;
    constexpr const char *magic = "clearjoint fe_stage rolling restart, version 1";

    std::string rank_file(const std::string &folder, const int rank)
    {
      return folder + "/rank-" + std::to_string(rank) + ".bin";
    }

    /// A JSON pointer (/rolling/n_steps) as the scene's key (rolling.n_steps).
    std::string key_of(const std::string &pointer)
    {
      std::string key = pointer.empty() ? std::string("(the scene)") : pointer.substr(1);
      for (auto &c : key)
        if (c == '/')
          c = '.';
      return key;
    }

    std::string value_at(const nlohmann::json &doc, const std::string &pointer)
    {
      const nlohmann::json::json_pointer p(pointer);
      return doc.contains(p) ? doc.at(p).dump() : std::string("(not set)");
    }
  }  // namespace

  RestartFolder::RestartFolder(std::string dir, MPI_Comm comm)
    : dir_(std::move(dir))
    , comm_(comm)
  {
    while (dir_.size() > 1 && dir_.back() == '/')
      dir_.pop_back();
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &n_ranks_);
  }

  void RestartFolder::write(const RestartWriter &bytes) const
  {
    const std::string writing = dir_ + "/writing", state = dir_ + "/state",
                      previous = dir_ + "/previous";
    write_collectively(comm_, [&] {
      if (rank_ != 0)
        return;
      std::error_code ec;
      fs::remove_all(writing, ec);  // a write cut short before
      fs::create_directories(writing, ec);
      if (ec)
        throw WriteError(writing, ec.message());
    });
    write_collectively(comm_, [&] {
      OutputFile file(rank_file(writing, rank_));
      file.stream().write(bytes.bytes().data(), std::streamsize(bytes.bytes().size()));
      file.close();
    });
    // every rank's file is complete: the swap (a kill inside it leaves `previous` whole)
    write_collectively(comm_, [&] {
      if (rank_ != 0)
        return;
      std::error_code ec;
      fs::remove_all(previous, ec);
      if (fs::exists(state))
        fs::rename(state, previous, ec);
      if (!ec)
        fs::rename(writing, state, ec);
      if (ec)
        throw WriteError(state, ec.message());
      fs::remove_all(previous, ec);
    });
  }

  std::string RestartFolder::complete_state(const std::string &dir)
  {
    for (const char *name : {"/state", "/previous"})
      if (fs::is_directory(dir + name))
        return dir + name;
    return "";
  }

  RestartReader RestartFolder::read() const
  {
    const std::string folder = complete_state(dir_);
    if (folder.empty())
      throw InputError("", "--resume", dir_,
                       "a folder with a complete restart state (" + dir_ + "/state)",
                       "written by fe_stage --write-restart");
    int files = 0;
    for (const auto &entry : fs::directory_iterator(folder))
      files += entry.path().extension() == ".bin" ? 1 : 0;
    if (files != n_ranks_)
      throw InputError("", "--resume", dir_,
                       "a restart state written by as many MPI ranks as this run has (" +
                         std::to_string(n_ranks_) + ")",
                       "it holds " + std::to_string(files) + " ranks' files: run with mpirun -np " +
                         std::to_string(files));
    std::string bytes;
    const std::string path = rank_file(folder, rank_);
    write_collectively(comm_, [&] { bytes = read_file(path); });
    return RestartReader(std::move(bytes), path);
  }

  RestartHeader RestartHeader::of(const FeScene &scene, const unsigned int n_ranks,
                                  const unsigned long long n_dofs)
  {
    nlohmann::json doc = scene_to_json(scene);
    doc.erase("output");  // fields or none, plots or none: the state is the same
    RestartHeader h;
    h.scene = doc.dump();
    h.n_ranks = n_ranks;
    h.n_dofs = n_dofs;
    return h;
  }

  void RestartHeader::write(RestartWriter &out) const
  {
    out.put_string(magic);
    out.put_string(scene);
    out.put(n_ranks);
    out.put(n_dofs);
    out.put(steps);
    out.put(time);
  }

  RestartHeader RestartHeader::read(RestartReader &in, const RestartHeader &expected)
  {
    if (in.get_string() != magic)
      in.damaged("it does not begin as one");
    RestartHeader h;
    h.scene = in.get_string();
    h.n_ranks = in.get<unsigned int>();
    h.n_dofs = in.get<unsigned long long>();
    h.steps = in.get<unsigned int>();
    h.time = in.get<double>();
    if (h.scene != expected.scene)
      {
        const nlohmann::json was = nlohmann::json::parse(h.scene, nullptr, false),
                             now = nlohmann::json::parse(expected.scene);
        if (was.is_discarded())
          in.damaged("its scene is not JSON");
        const nlohmann::json patch = nlohmann::json::diff(was, now);
        const std::string pointer = patch.empty() ? "" : patch[0].value("path", "");
        throw InputError("", key_of(pointer), value_at(now, pointer),
                         "the value the restart state was written with, " + value_at(was, pointer),
                         in.path() + " continues another scene (" + std::to_string(patch.size()) +
                           " keys differ); only output.* may change between the runs");
      }
    if (h.n_ranks != expected.n_ranks)
      in.damaged("written by " + std::to_string(h.n_ranks) + " ranks, read by " +
                 std::to_string(expected.n_ranks));
    if (h.n_dofs != expected.n_dofs)
      in.damaged("its mesh had " + std::to_string(h.n_dofs) + " DoFs, this one has " +
                 std::to_string(expected.n_dofs) + " (another build of fe_stage?)");
    return h;
  }
}  // namespace clearjoint::fe::detail
