#include "common/atomic_file.h"

#include "common/error.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <streambuf>
#include <vector>

namespace clearjoint
{
  namespace detail
  {
    /// A write buffer over a descriptor that keeps the errno of the first failed write (the
    /// reason std::ofstream forgets).
    class FdBuf : public std::streambuf
    {
    public:
      explicit FdBuf(const int fd)
        : fd_(fd)
        , buffer_(1 << 16)
      {
        setp(buffer_.data(), buffer_.data() + buffer_.size());
      }
      ~FdBuf() override
      {
        if (fd_ >= 0)
          ::close(fd_);
      }

      int error() const { return error_; }

      /// Flushes and closes; returns the first error (0 if none).
      int close()
      {
        sync();
        if (fd_ >= 0 && ::close(fd_) != 0 && error_ == 0)
          error_ = errno;
        fd_ = -1;
        return error_;
      }

    protected:
      int_type overflow(const int_type c) override
      {
        if (!flush_buffer())
          return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof()))
        {
          *pptr() = traits_type::to_char_type(c);
          pbump(1);
        }
        return traits_type::not_eof(c);
      }
      int sync() override { return flush_buffer() ? 0 : -1; }

    private:
      bool flush_buffer()
      {
        const char *p = pbase();
        std::size_t left = std::size_t(pptr() - pbase());
        if (error_ != 0 || fd_ < 0)
        {
          setp(buffer_.data(), buffer_.data() + buffer_.size());  // drop: already failed
          return false;
        }
        while (left > 0)
        {
          const ssize_t n = ::write(fd_, p, left);
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
          {
            error_ = n < 0 ? errno : ENOSPC;
            break;
          }
          p += n;
          left -= std::size_t(n);
        }
        setp(buffer_.data(), buffer_.data() + buffer_.size());
        return error_ == 0;
      }

      int fd_;
      int error_ = 0;
      std::vector<char> buffer_;
    };
  } // namespace detail

  OutputFile::OutputFile(const std::string &path)
    : path_(path)
  {
    int fd;
    do
      fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    while (fd < 0 && errno == EINTR);
    if (fd < 0)
    {
      const int e = errno;
      if (is_write_failure(e))
        throw WriteError(path, e);
      throw InputError("cannot create output file '" + path + "': " + std::strerror(e));
    }
    buf_ = std::make_unique<detail::FdBuf>(fd);
    out_ = std::make_unique<std::ostream>(buf_.get());  // the stream's defaults (precision 6)
  }

  OutputFile::~OutputFile() = default;

  void OutputFile::check() const
  {
    if (buf_->error() != 0)
      throw WriteError(path_, buf_->error());
  }

  void OutputFile::close()
  {
    out_->flush();
    if (const int e = buf_->close(); e != 0)
      throw WriteError(path_, e);
    if (!*out_)
      throw WriteError(path_, EIO);
  }

  void write_file(const std::string &path, const std::function<void(std::ostream &)> &write)
  {
    OutputFile f(path);
    try
    {
      write(f.stream());
    }
    catch (const WriteError &)
    {
      throw;
    }
    catch (const std::exception &)
    {
      f.stream().flush();
      f.check();  // the writer gave up because a write failed: say which and why
      throw;
    }
    f.close();
  }

  AtomicFile::AtomicFile(const std::string &path)
    : path_(path)
    , tmp_path_(path + ".tmp." + std::to_string(::getpid()))
    , temporary_(tmp_path_)
  {
    try
    {
      file_ = std::make_unique<OutputFile>(tmp_path_);
      file_->stream().precision(17);
    }
    catch (const WriteError &e)
    {
      throw WriteError(path_, e.reason());
    }
  }

  AtomicFile::~AtomicFile()
  {
    if (!committed_)
    {
      file_.reset();
      std::remove(tmp_path_.c_str());
    }
  }

  void AtomicFile::check() const
  {
    try
    {
      file_->check();
    }
    catch (const WriteError &e)
    {
      throw WriteError(path_, e.reason());
    }
  }

  void AtomicFile::commit()
  {
    try
    {
      file_->close();
    }
    catch (const WriteError &e)
    {
      throw WriteError(path_, e.reason());
    }
    if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0)
      throw WriteError(path_, std::string("cannot rename '") + tmp_path_ +
                                "' to it: " + std::strerror(errno));
    committed_ = true;
    temporary_.release();
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
