// SHA-256 against the test vectors of FIPS 180-2 (Appendix B) and the
// empty message.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "core/sha256.hpp"

namespace railvsi::scheduler {
namespace {

TEST(Sha256, OneBlockMessageOfFips180_2) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, MultiBlockMessageOfFips180_2) {
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, LongMessageOfFips180_2InPieces) {
  // One million 'a', fed in uneven pieces to cross block boundaries.
  Sha256 h;
  const std::string piece(997, 'a');
  std::size_t fed = 0;
  while (fed + piece.size() <= 1000000) {
    h.update(piece);
    fed += piece.size();
  }
  h.update(std::string(1000000 - fed, 'a'));
  EXPECT_EQ(h.hex_digest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, EmptyMessage) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, FiftyFiveAndFiftySixBytesPadDifferently) {
  // 55 bytes fit the length in the same block, 56 need a second one.
  // Reference digests from Python's hashlib (sha256(b"a" * n)).
  EXPECT_EQ(sha256_hex(std::string(55, 'a')), "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(sha256_hex(std::string(56, 'a')), "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
}

TEST(Sha256, CpuInstructionsAgreeWithThePortableCode) {
  // Messages of 0 to 300 bytes (every padding case, several blocks) with
  // varied bytes, fed whole and in pieces of 7: both engines must give the
  // same digest (the known vectors above check the default engine).
  std::string message;
  for (std::size_t n = 0; n <= 300; ++n) {
    Sha256 portable(Sha256::Engine::kPortable), automatic, pieces;
    portable.update(message);
    automatic.update(message);
    for (std::size_t at = 0; at < message.size(); at += 7) pieces.update(std::string_view(message).substr(at, 7));
    const std::string expected = portable.hex_digest();
    ASSERT_EQ(automatic.hex_digest(), expected) << n << " bytes";
    ASSERT_EQ(pieces.hex_digest(), expected) << n << " bytes";
    message += static_cast<char>((n * 131 + 17) & 0xff);
  }
  EXPECT_EQ(Sha256(Sha256::Engine::kPortable).update("abc").hex_digest(),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  RecordProperty("cpu_instructions", Sha256::cpu_instructions() ? "yes" : "no");
}

}  // namespace
}  // namespace railvsi::scheduler
