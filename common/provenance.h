// Provenance of result files: the program version, SHA-256 digests of inputs
// and the host CPU, which a study runner keys its cache of runs on.
//
// SHA-256 is FIPS 180-4, computed by OpenSSL's libcrypto (EVP interface).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

struct evp_md_ctx_st;  // OpenSSL's EVP_MD_CTX

namespace granasym {

// The version of this build: "<project version>+<git describe --always
// --dirty --tags>" of the source tree, taken when the program was built (not
// when it was configured), e.g. "0.1.0+v0.1-12-g8d3c924-dirty"; outside a git
// checkout or without git "granasym <project version> (no git)".
std::string ProgramVersion();

// The CPU model of this host: the "model name" of /proc/cpuinfo with its
// blanks collapsed, or the machine type from uname (e.g. "aarch64") where
// there is none; "unknown" when neither is available.
std::string HostCpuModel();

// The hardware threads of this machine (at least 1).
int HardwareThreads();

// SHA-256 of `bytes` as 64 lower-case hexadecimal characters.
std::string Sha256Hex(std::string_view bytes);

namespace internal {
// Scalar type and count per element of the vectors Sha256 hashes by value.
template <typename T>
struct HashedElement {
  static constexpr bool kValid = std::is_arithmetic_v<T> && !std::is_same_v<T, bool>;
  using Scalar = T;
  static constexpr size_t kCount = 1;
};
template <typename T, size_t N>
struct HashedElement<std::array<T, N>> {
  static constexpr bool kValid = HashedElement<T>::kValid;
  using Scalar = typename HashedElement<T>::Scalar;
  static constexpr size_t kCount = N * HashedElement<T>::kCount;
};
}  // namespace internal

// Incremental SHA-256: Update with the pieces in order, then HexDigest. The
// pieces are concatenated without separators; callers hashing several fields
// frame them (a name, a length) where a different split could give the same
// bytes.
class Sha256 {
 public:
  Sha256();  // RuntimeError when OpenSSL cannot set up the digest
  Sha256(Sha256&& other) noexcept;
  Sha256& operator=(Sha256&& other) noexcept;
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  ~Sha256();

  // Appends `size` bytes at `data` (which may be null when `size` is 0).
  void Update(const void* data, size_t size);
  void Update(std::string_view bytes) { Update(bytes.data(), bytes.size()); }
  // Appends the values' bytes in little-endian order whatever the host (a
  // double as its IEEE-754 binary64 bit pattern, so 0.0 and −0.0 differ),
  // so that digests agree across machines. Elements are numbers or
  // std::arrays of numbers (positions); no length is added.
  template <typename T>
  void Update(const std::vector<T>& values) {
    using Element = internal::HashedElement<T>;
    static_assert(Element::kValid, "Sha256 hashes vectors of numbers or arrays of numbers");
    static_assert(sizeof(T) == Element::kCount * sizeof(typename Element::Scalar),
                  "element with padding");
    UpdateLittleEndian(values.data(), values.size() * Element::kCount,
                       sizeof(typename Element::Scalar));
  }

  // Digest of everything appended so far (64 lower-case hexadecimal
  // characters); the hash may continue with further Updates.
  std::string HexDigest() const;

 private:
  struct ContextDeleter {
    void operator()(evp_md_ctx_st* context) const;
  };
  void UpdateLittleEndian(const void* data, size_t count, size_t scalar_size);

  std::unique_ptr<evp_md_ctx_st, ContextDeleter> context_;
};

}  // namespace granasym
