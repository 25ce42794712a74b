#include "core/model/sha256.hpp"

#include <openssl/evp.h>

#include "core/error.hpp"

namespace gacompare::core {

std::string sha256_hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  // An empty string_view may carry a null data pointer; hand OpenSSL a valid one.
  const void* data = bytes.empty() ? static_cast<const void*>("") : bytes.data();
  if (EVP_Digest(data, bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1 || length != 32)
    throw run_error("sha256: OpenSSL EVP_Digest failed");
  static constexpr char hex[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * length);
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 0xF];
  }
  return out;
}

}  // namespace gacompare::core
