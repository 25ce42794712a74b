#pragma once
// SHA-256 of a byte string, as 64 lower-case hex digits (OpenSSL libcrypto).
// Used to stamp results with the exact scene file that produced them.
#include <string>
#include <string_view>

namespace gacompare::core {

std::string sha256_hex(std::string_view bytes);

}  // namespace gacompare::core
