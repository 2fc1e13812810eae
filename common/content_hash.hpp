#pragma once

#include <string>
#include <string_view>

namespace isg::common {

// "sha256:" and the SHA-256 of `bytes` in lower-case hex (Debian's nettle): what identifies a
// world's content in sweep.json and metrics.json, so that results of two different buildings of
// one name are never mixed.
std::string contentHash(std::string_view bytes);

// A name-based UUID (RFC 4122, version 5: SHA-1 of `namespace_uuid`'s 16 bytes and `name`), in
// lower case: "2ed6657d-e927-568b-95e1-2665a8aea6a2". The same name gives the same UUID on every
// machine and run, so that files naming things by UUID (BCF topics) are reproducible.
// `namespace_uuid` is a UUID in that form (throws std::invalid_argument otherwise).
std::string nameUuid(std::string_view namespace_uuid, std::string_view name);

}  // namespace isg::common
