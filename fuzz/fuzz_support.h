// Shared by the fuzz targets: every reader must answer hostile bytes with an InputError (the
// documented "exit 1, message naming the key") and nothing else. Any other exception is a
// finding: it would surface as "unexpected failure" (exit 2) or a crash, so abort() to make
// libFuzzer (or the replay driver) report it with the input that caused it.
#pragma once

#include "common/error.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace clearjoint::fuzz
{
  template <typename F>
  void expect_only_input_errors(F &&f)
  {
    try
    {
      f();
    }
    catch (const InputError &)
    {
    }
    catch (const std::exception &e)
    {
      std::fprintf(stderr, "fuzz finding: not an InputError: %s\n", e.what());
      std::abort();
    }
  }

  inline std::string text_of(const std::uint8_t *data, std::size_t size)
  {
    return std::string(reinterpret_cast<const char *>(data), size);
  }
} // namespace clearjoint::fuzz
