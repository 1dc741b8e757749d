#include "common/atomic_file.h"

#include "common/error.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace clearjoint
{
  AtomicFile::AtomicFile(const std::string &path)
    : path_(path)
    , tmp_path_(path + ".tmp." + std::to_string(::getpid()))
    , out_(tmp_path_, std::ios::out | std::ios::trunc | std::ios::binary)
  {
    if (!out_)
      throw InputError("cannot create output file '" + path + "': " + std::strerror(errno));
    out_.precision(17);
  }

  AtomicFile::~AtomicFile()
  {
    if (!committed_)
    {
      out_.close();
      std::remove(tmp_path_.c_str());
    }
  }

  void AtomicFile::commit()
  {
    out_.flush();
    const bool ok = static_cast<bool>(out_);
    out_.close();
    if (!ok)
      throw std::runtime_error("writing '" + path_ + "' failed (disk full?)");
    if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0)
      throw std::runtime_error("cannot rename '" + tmp_path_ + "' to '" + path_ +
                               "': " + std::strerror(errno));
    committed_ = true;
  }

  void write_file_atomically(const std::string &path, const std::string &content)
  {
    AtomicFile f(path);
    f.stream() << content;
    f.commit();
  }

  std::string read_file(const std::string &path)
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw InputError("cannot read file '" + path + "': " + std::strerror(errno));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
} // namespace clearjoint
