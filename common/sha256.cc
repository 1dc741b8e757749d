#include "common/sha256.h"

#include "common/atomic_file.h"

#include <openssl/evp.h>

#include <memory>
#include <stdexcept>

namespace clearjoint
{
  std::string sha256_hex(const std::string &bytes)
  {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                &EVP_MD_CTX_free);
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1 ||
        EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size()) != 1 ||
        EVP_DigestFinal_ex(ctx.get(), digest, &length) != 1)
      throw std::runtime_error("OpenSSL SHA-256 failed");
    static const char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(2 * length);
    for (unsigned int i = 0; i < length; ++i)
    {
      out.push_back(hex[digest[i] >> 4]);
      out.push_back(hex[digest[i] & 0xf]);
    }
    return out;
  }

  std::string sha256_file(const std::string &path) { return sha256_hex(read_file(path)); }
} // namespace clearjoint
