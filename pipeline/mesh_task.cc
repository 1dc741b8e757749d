#include "pipeline/mesh_task.h"

#include "common/error.h"
#include "common/sha256.h"
#include "pipeline/pipeline_config.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  std::optional<std::string> geo_to_mesh(const nlohmann::json &scene, const std::string &scene_file)
  {
    const nlohmann::json *mesh = find_key_path(scene, "geometry.mesh");
    if (!mesh || mesh->is_null())
      return std::nullopt;
    const std::string allowed =
      "an existing Gmsh file: FILE.msh (MSH 2.2 with the physical groups of docs/geometry.md) "
      "or FILE.geo (meshed by run_pipeline with scripts/make_mesh); a relative path is taken "
      "from the base scene's folder, or in pipeline.yaml overrides from the folder "
      "run_pipeline runs in";
    if (!mesh->is_string())
      throw InputError(scene_file, "geometry.mesh", mesh->dump(), allowed);
    const std::string path = mesh->get<std::string>();
    const std::string ext = fs::path(path).extension().string();
    std::error_code ec;
    if (path.empty() || path[0] != '/' || !fs::is_regular_file(path, ec))
      throw InputError(scene_file, "geometry.mesh", path, allowed, "no such file");
    if (ext == ".geo")
      return path;
    if (ext == ".msh")
      return std::nullopt;
    throw InputError(scene_file, "geometry.mesh", path, allowed, "unknown extension '" + ext + "'");
  }

  std::vector<std::string> geo_files(const std::string &geo)
  {
    std::vector<std::string> out;
    std::vector<std::string> todo = {fs::canonical(geo).string()};
    const std::regex include(R"re(^\s*Include\s*"([^"]+)")re");
    while (!todo.empty())
    {
      const std::string file = todo.back();
      todo.pop_back();
      if (std::find(out.begin(), out.end(), file) != out.end())
        continue;
      out.push_back(file);
      std::ifstream in(file);
      std::string line;
      std::smatch m;
      while (std::getline(in, line))
        if (std::regex_search(line, m, include))
        {
          const fs::path inc = fs::path(file).parent_path() / m[1].str();
          std::error_code ec;
          if (fs::is_regular_file(inc, ec))
            todo.push_back(fs::canonical(inc).string());
        }
    }
    return out;
  }

  std::string make_mesh_script()
  {
    if (const char *env = std::getenv("CLEARJOINT_MAKE_MESH"); env && *env)
      return env;
    return std::string(CLEARJOINT_SOURCE_DIR) + "/scripts/make_mesh";
  }

  bool gmsh_on_path()
  {
    const char *path = std::getenv("PATH");
    if (!path)
      return false;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':'))
      if (!dir.empty() && ::access((fs::path(dir) / "gmsh").c_str(), X_OK) == 0)
        return true;
    return false;
  }

  Task make_mesh_task(const std::string &geo, const std::map<std::string, double> &joint,
                      const std::map<std::string, double> &parameters, const std::string &run_dir,
                      const std::string &build_dir)
  {
    Task t;
    t.stage = "make_mesh";
    t.executable = make_mesh_script();
    // make_mesh finds msh_check through $MSH_CHECK: ours, from the build the stages come from.
    t.launcher = {"/usr/bin/env", "MSH_CHECK=" + (fs::path(build_dir) / "geometry" / "msh_check").string()};
    t.args = {geo, "{out}/mesh.msh"};
    std::map<std::string, double> numbers = joint;
    for (const auto &[name, value] : parameters)
      numbers[name] = value;
    for (const auto &[name, value] : numbers)
      for (const auto &a : {std::string("-setnumber"), name, value_label(value)})
        t.args.push_back(a);
    t.input_files = geo_files(geo);
    std::string key;
    for (const auto &a : t.args)
      key += a + '\n';
    const std::string stem = fs::path(geo).stem().string();
    t.output_dir = (fs::path(run_dir) / "mesh" / (stem + "-" + sha256_hex(key).substr(0, 12))).string();
    t.name = "mesh/" + fs::path(t.output_dir).filename().string();
    return t;
  }

  void check_geo_parses(const Task &mesh, const std::string &where)
  {
    const std::string geo = mesh.args.at(0);
    const std::string base =
      (fs::temp_directory_path() / ("clearjoint-geo-check-" + std::to_string(::getpid()))).string();
    std::vector<std::string> words = {"gmsh", "-0", geo};
    words.insert(words.end(), mesh.args.begin() + 2, mesh.args.end());  // -setnumber NAME VALUE
    words.insert(words.end(), {"-o", base + ".geo_unrolled"});
    std::error_code ec;
    fs::remove(base + ".log", ec);
    const int status = run_process(words, base + ".log");
    std::string log;
    {
      std::ifstream in(base + ".log");
      std::stringstream text;
      text << in.rdbuf();
      log = text.str();
    }
    fs::remove(base + ".log", ec);
    fs::remove(base + ".geo_unrolled", ec);
    // gmsh often exits 0 after an error: its "Error" lines decide too (as in make_mesh).
    std::string error;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("Error", 0) == 0)
      {
        error = line;
        break;
      }
    const bool exited_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (exited_ok && error.empty())
      return;
    if (error.empty())
      error = "gmsh exited with status " +
              std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    throw InputError(where, "geometry.mesh", geo,
                     "a .geo file Gmsh reads (with the scene's joint dimensions and the sweep's "
                     "mesh_parameters)",
                     "gmsh -0: " + error);
  }
} // namespace clearjoint::pipeline
