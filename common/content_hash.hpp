#pragma once

#include <string>
#include <string_view>

namespace isg::common {

// "sha256:" and the SHA-256 of `bytes` in lower-case hex (Debian's nettle): what identifies a
// world's content in sweep.json and metrics.json, so that results of two different buildings of
// one name are never mixed.
std::string contentHash(std::string_view bytes);

}  // namespace isg::common
