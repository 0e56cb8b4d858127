// SHA-256 of a model file's bytes, for the export's provenance line: OpenSSL's libcrypto
// (libssl-dev), the digest Debian's own tools use.
#include <openssl/evp.h>

#include <string>

#include "sysid/deploy.hpp"
#include "sysid/error.hpp"

namespace sysid {

std::string Sha256Hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1 ||
      size != 32)
    throw InternalError("SHA-256: libcrypto's EVP_Digest failed");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * size);
  for (unsigned int i = 0; i < size; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 0xF];
  }
  return hex;
}

}  // namespace sysid
