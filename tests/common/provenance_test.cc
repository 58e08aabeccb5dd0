#include "common/provenance.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace granasym {
namespace {

// FIPS 180-2 Appendix B (SHA-256 examples), also NIST's CAVP short messages.
constexpr char kEmptyDigest[] = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";
constexpr char kAbcDigest[] = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
constexpr char kTwoBlockMessage[] = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
constexpr char kTwoBlockDigest[] =
    "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1";
constexpr char kMillionADigest[] =
    "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0";

TEST(Sha256, OneShotDigestsMatchTheFipsTestVectors) {
  EXPECT_EQ(Sha256Hex(""), kEmptyDigest);
  EXPECT_EQ(Sha256Hex("abc"), kAbcDigest);
  EXPECT_EQ(Sha256Hex(kTwoBlockMessage), kTwoBlockDigest);
  EXPECT_EQ(Sha256Hex(std::string(1000000, 'a')), kMillionADigest);
}

TEST(Sha256, IncrementalDigestsMatchTheFipsTestVectors) {
  EXPECT_EQ(Sha256().HexDigest(), kEmptyDigest);
  Sha256 abc;
  abc.Update("a");
  abc.Update(std::string_view("bc"));
  EXPECT_EQ(abc.HexDigest(), kAbcDigest);
  // A million 'a' in uneven pieces that straddle the 64-byte blocks.
  const std::string piece(997, 'a');
  Sha256 million;
  size_t fed = 0;
  while (fed + piece.size() <= 1000000) {
    million.Update(piece.data(), piece.size());
    fed += piece.size();
  }
  million.Update(piece.data(), 1000000 - fed);
  EXPECT_EQ(million.HexDigest(), kMillionADigest);
}

TEST(Sha256, IncrementalEqualsOneShotForEverySplit) {
  const std::string message = kTwoBlockMessage;
  for (size_t split = 0; split <= message.size(); ++split) {
    Sha256 hash;
    hash.Update(message.data(), split);
    hash.Update(message.data() + split, message.size() - split);
    EXPECT_EQ(hash.HexDigest(), Sha256Hex(message)) << split;
  }
}

TEST(Sha256, DigestCanBeTakenMidwayAndTheHashContinues) {
  Sha256 hash;
  hash.Update("ab");
  EXPECT_EQ(hash.HexDigest(), Sha256Hex("ab"));
  EXPECT_EQ(hash.HexDigest(), Sha256Hex("ab"));
  hash.Update("c");
  EXPECT_EQ(hash.HexDigest(), kAbcDigest);
  Sha256 moved = std::move(hash);
  moved.Update("d");
  EXPECT_EQ(moved.HexDigest(), Sha256Hex("abcd"));
}

TEST(Sha256, VectorsOfDoublesAreHashedAsLittleEndianBinary64) {
  // 1.0 = 0x3FF0000000000000, −2.5 = 0xC004000000000000.
  const std::string bytes("\x00\x00\x00\x00\x00\x00\xf0\x3f\x00\x00\x00\x00\x00\x00\x04\xc0", 16);
  Sha256 hash;
  hash.Update(std::vector<double>{1.0, -2.5});
  EXPECT_EQ(hash.HexDigest(), Sha256Hex(bytes));
  // Positions as arrays hash as their flattened components.
  Sha256 positions, flat;
  positions.Update(std::vector<std::array<double, 3>>{{0.1, 0.2, 0.3}, {1e-3, -4.0, 5e5}});
  flat.Update(std::vector<double>{0.1, 0.2, 0.3, 1e-3, -4.0, 5e5});
  EXPECT_EQ(positions.HexDigest(), flat.HexDigest());
  // Bit identity: 0.0 and −0.0 are different inputs.
  Sha256 zero, negative_zero;
  zero.Update(std::vector<double>{0.0});
  negative_zero.Update(std::vector<double>{-0.0});
  EXPECT_NE(zero.HexDigest(), negative_zero.HexDigest());
  // Integers too: 0x0102030405060708 as 08 07 .. 01.
  Sha256 integers;
  integers.Update(std::vector<int64_t>{0x0102030405060708});
  EXPECT_EQ(integers.HexDigest(), Sha256Hex(std::string("\x08\x07\x06\x05\x04\x03\x02\x01", 8)));
  // An empty vector adds nothing.
  Sha256 empty;
  empty.Update(std::vector<double>{});
  EXPECT_EQ(empty.HexDigest(), kEmptyDigest);
}

TEST(ProgramVersion, StartsWithTheProjectVersion) {
  const std::string project = GRANASYM_PROJECT_VERSION;
  const std::string version = ProgramVersion();
  ASSERT_FALSE(version.empty());
  EXPECT_EQ(version.find('\n'), std::string::npos) << version;
  if (version == "granasym " + project + " (no git)") return;  // built outside a git checkout
  ASSERT_EQ(version.rfind(project + "+", 0), 0u) << version;
  // The git description follows: non-empty, one word.
  const std::string describe = version.substr(project.size() + 1);
  EXPECT_FALSE(describe.empty()) << version;
  EXPECT_EQ(describe.find(' '), std::string::npos) << version;
}

TEST(HostCpuModel, IsOneNonEmptyLine) {
  const std::string model = HostCpuModel();
  ASSERT_FALSE(model.empty());
  EXPECT_EQ(model.find('\n'), std::string::npos) << model;
  EXPECT_NE(model.front(), ' ') << model;
  EXPECT_NE(model.back(), ' ') << model;
  EXPECT_EQ(model.find("  "), std::string::npos) << model;
}

}  // namespace
}  // namespace granasym
