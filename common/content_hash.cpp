#include "common/content_hash.hpp"

#include <nettle/sha1.h>
#include <nettle/sha2.h>

#include <array>
#include <stdexcept>

namespace isg::common {

std::string contentHash(std::string_view bytes) {
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(&context, digest.size(), digest.data());
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "sha256:";
  for (const std::uint8_t b : digest) {
    out += kHex[b >> 4];
    out += kHex[b & 15];
  }
  return out;
}

std::string nameUuid(std::string_view namespace_uuid, std::string_view name) {
  auto nibble = [&](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    throw std::invalid_argument("not a UUID: " + std::string(namespace_uuid));
  };
  std::array<std::uint8_t, 16> space{};
  std::size_t byte = 0;
  for (std::size_t i = 0; i < namespace_uuid.size(); ++i) {
    if (namespace_uuid[i] == '-' && (i == 8 || i == 13 || i == 18 || i == 23)) continue;
    if (byte == 16 || i + 1 >= namespace_uuid.size()) {
      throw std::invalid_argument("not a UUID: " + std::string(namespace_uuid));
    }
    space[byte++] = std::uint8_t(nibble(namespace_uuid[i]) << 4 | nibble(namespace_uuid[i + 1]));
    ++i;
  }
  if (byte != 16 || namespace_uuid.size() != 36) {
    throw std::invalid_argument("not a UUID: " + std::string(namespace_uuid));
  }
  sha1_ctx context;
  sha1_init(&context);
  sha1_update(&context, space.size(), space.data());
  sha1_update(&context, name.size(), reinterpret_cast<const std::uint8_t*>(name.data()));
  std::array<std::uint8_t, SHA1_DIGEST_SIZE> digest{};
  sha1_digest(&context, digest.size(), digest.data());
  digest[6] = std::uint8_t((digest[6] & 0x0F) | 0x50);  // version 5
  digest[8] = std::uint8_t((digest[8] & 0x3F) | 0x80);  // the RFC 4122 variant
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (int i = 0; i < 16; ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) out += '-';
    out += kHex[digest[i] >> 4];
    out += kHex[digest[i] & 15];
  }
  return out;
}

}  // namespace isg::common
