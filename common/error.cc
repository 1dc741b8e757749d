#include "common/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace clearjoint
{
  namespace
  {
    std::string compose(const std::string &file, const std::string &key_path,
                        const std::string &value, const std::string &allowed,
                        const std::string &detail)
    {
      std::string m = "input error";
      if (!file.empty())
        m += " in " + file;
      if (!key_path.empty())
        m += ": key '" + key_path + "'";
      if (!value.empty())
        // Without a key ("input error in f.yaml: value '0xFF'; allowed: UTF-8 text (...)").
        m += (key_path.empty() ? ": value '" : " has value '") + value + "'";
      if (!allowed.empty())
        m += "; allowed: " + allowed;
      if (!detail.empty())
        m += " (" + detail + ")";
      return m;
    }
  } // namespace

  InputError::InputError(std::string file, std::string key_path, std::string value,
                         std::string allowed, std::string detail)
    : std::runtime_error(compose(file, key_path, value, allowed, detail))
    , file_(std::move(file))
    , key_path_(std::move(key_path))
  {}

  InputError::InputError(const std::string &message)
    : std::runtime_error("input error: " + message)
  {}

  WriteError::WriteError(const std::string &path, const int os_error)
    : WriteError(path, std::string(std::strerror(os_error != 0 ? os_error : EIO)))
  {}

  WriteError::WriteError(const std::string &path, const std::string &reason)
    : std::runtime_error("cannot write '" + path + "': " + reason)
    , path_(path)
    , reason_(reason)
  {}

  bool is_write_failure(const int os_error)
  {
    return os_error == ENOSPC || os_error == EDQUOT || os_error == EIO || os_error == EROFS ||
           os_error == EFBIG;
  }

  std::string format_value(const double value)
  {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6g", value);
    return buf;
  }
} // namespace clearjoint
