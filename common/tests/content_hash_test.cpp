// Content hashes and name-based UUIDs against values computed elsewhere: sha256sum, and RFC 4122's
// version 5 as Python's uuid.uuid5 gives it.
#include "common/content_hash.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace isg::common {
namespace {

TEST(ContentHash, IsTheSha256OfTheBytes) {
  // printf abc | sha256sum
  EXPECT_EQ(contentHash("abc"),
            "sha256:ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(NameUuid, IsRfc4122Version5) {
  // python3 -c "import uuid; print(uuid.uuid5(uuid.NAMESPACE_DNS, 'python.org'))"
  EXPECT_EQ(nameUuid("6ba7b810-9dad-11d1-80b4-00c04fd430c8", "python.org"),
            "886313e1-3b8a-5372-9b90-0c9aee199e5d");
  // The namespace in upper case is the same namespace.
  EXPECT_EQ(nameUuid("6BA7B810-9DAD-11D1-80B4-00C04FD430C8", "python.org"),
            "886313e1-3b8a-5372-9b90-0c9aee199e5d");
  EXPECT_NE(nameUuid("6ba7b810-9dad-11d1-80b4-00c04fd430c8", "python.org."),
            "886313e1-3b8a-5372-9b90-0c9aee199e5d");
}

TEST(NameUuid, RefusesANamespaceThatIsNotAUuid) {
  for (const char* bad :
       {"", "6ba7b810-9dad-11d1-80b4-00c04fd430c", "6ba7b8109dad11d180b400c04fd430c8",
        "6ba7b810-9dad-11d1-80b4-00c04fd430cg", "6ba7b810-9dad-11d1-80b4-00c04fd430c8a"}) {
    EXPECT_THROW(nameUuid(bad, "x"), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace isg::common
