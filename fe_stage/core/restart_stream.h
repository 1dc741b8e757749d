// The bytes of a restart file (the rolling study's, solve/rolling_restart.h): each owner of
// state writes its values in order and reads them back in the same order. Values are written
// as their bytes (the same machine and build read them back); named sections mark where each
// owner's part begins, so a reader out of step — a file from another version, a damaged one —
// stops at the next section with its name instead of reading nonsense. No deal.II.
#pragma once

#include "common/error.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace clearjoint::fe
{
  class RestartWriter
  {
  public:
    template <typename T>
    void put(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>, "written as bytes");
      bytes_.append(reinterpret_cast<const char *>(&value), sizeof(T));
    }
    template <typename T>
    void put_vector(const std::vector<T> &values)
    {
      static_assert(std::is_trivially_copyable_v<T>, "written as bytes");
      put<std::uint64_t>(values.size());
      bytes_.append(reinterpret_cast<const char *>(values.data()), values.size() * sizeof(T));
    }
    void put_string(const std::string &text)
    {
      put<std::uint64_t>(text.size());
      bytes_.append(text);
    }
    /// Where an owner's part begins.
    void section(const std::string &name) { put_string("section " + name); }

    const std::string &bytes() const { return bytes_; }

  private:
    std::string bytes_;
  };

  class RestartReader
  {
  public:
    /// `bytes`: a file's whole content; `path`: its name for the messages.
    RestartReader(std::string bytes, std::string path)
      : bytes_(std::move(bytes))
      , path_(std::move(path))
    {}

    template <typename T>
    T get()
    {
      static_assert(std::is_trivially_copyable_v<T>, "read as bytes");
      T value;
      std::memcpy(&value, take(sizeof(T)), sizeof(T));
      return value;
    }
    template <typename T>
    std::vector<T> get_vector()
    {
      static_assert(std::is_trivially_copyable_v<T>, "read as bytes");
      const auto n = get<std::uint64_t>();
      if (n > (bytes_.size() - at_) / sizeof(T))
        damaged("it ends early: a list of " + std::to_string(n) + " values runs past its end");
      std::vector<T> values(n);
      std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
      return values;
    }
    std::string get_string()
    {
      const auto n = get<std::uint64_t>();
      if (n > bytes_.size() - at_)
        damaged("it ends early: a text of " + std::to_string(n) + " bytes runs past its end");
      return std::string(take(n), n);
    }
    /// The next owner's part must begin here.
    void section(const std::string &name)
    {
      const std::string found = get_string();
      if (found != "section " + name)
        damaged("expected the section '" + name + "', found '" + found.substr(0, 40) + "'");
    }
    /// The whole file was read.
    void expect_end() const
    {
      if (at_ != bytes_.size())
        damaged(std::to_string(bytes_.size() - at_) + " bytes left over at its end");
    }
    /// A check on what was read: its failure is the file's.
    [[noreturn]] void damaged(const std::string &why) const
    {
      throw InputError(path_ + ": not a restart file this fe_stage can read (" + why +
                       "); write it again with --write-restart");
    }
    const std::string &path() const { return path_; }

  private:
    const char *take(const std::size_t n)
    {
      if (n > bytes_.size() - at_)
        damaged("it ends early, at byte " + std::to_string(bytes_.size()));
      const char *p = bytes_.data() + at_;
      at_ += n;
      return p;
    }

    std::string bytes_, path_;
    std::size_t at_ = 0;
  };
}  // namespace clearjoint::fe
