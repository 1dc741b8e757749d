// SHA-256 of files and strings (hex), for provenance in manifests and law files.
#pragma once

#include <string>

namespace clearjoint
{
  std::string sha256_hex(const std::string &bytes);
  /// Throws InputError naming the file if it cannot be read.
  std::string sha256_file(const std::string &path);
} // namespace clearjoint
