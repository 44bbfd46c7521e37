// SHA-256 against the FIPS 180-4 / NIST example vectors, across block boundaries.
#include <doctest/doctest.h>

#include <string>

#include "core/sha256.hpp"

using namespace quadapt;

TEST_CASE("sha256: NIST vectors") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256_hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("sha256: incremental updates of any size give the one-shot digest") {
  std::string s;
  for (int i = 0; i < 300; ++i) s += static_cast<char>(i * 37 + 11);
  const std::string whole = sha256_hex(s);
  for (size_t step : {1u, 3u, 55u, 56u, 63u, 64u, 65u, 200u}) {
    Sha256 h;
    for (size_t i = 0; i < s.size(); i += step) h.update(s.data() + i, std::min(step, s.size() - i));
    CHECK(h.hex() == whole);
  }
}
