#include "common/provenance.h"

#include <openssl/err.h>
#include <openssl/evp.h>
#include <sys/utsname.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <thread>

#include "common/error.h"
#include "common/results_version.h"
#include "program_version.h"  // generated at build time (common/write_program_version.cmake)

namespace granasym {
namespace {

// Names the failing OpenSSL call and OpenSSL's own reason.
[[noreturn]] void Fail(const std::string& call) {
  char reason[256] = "no reason recorded";
  if (const unsigned long code = ERR_get_error(); code != 0) {
    ERR_error_string_n(code, reason, sizeof(reason));
  }
  ERR_clear_error();
  throw RuntimeError("OpenSSL call " + call + " failed for SHA-256: " + reason);
}

std::string Hex(const unsigned char* digest, unsigned int size) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text(2 * size, '0');
  for (unsigned int k = 0; k < size; ++k) {
    text[2 * k] = kDigits[digest[k] >> 4];
    text[2 * k + 1] = kDigits[digest[k] & 0xf];
  }
  return text;
}

// Trims and collapses runs of blanks: "Intel(R)  Xeon(R) ..." pads with spaces.
std::string CollapseBlanks(const std::string& text) {
  std::string collapsed;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!collapsed.empty() && collapsed.back() != ' ') collapsed.push_back(' ');
    } else {
      collapsed.push_back(c);
    }
  }
  if (!collapsed.empty() && collapsed.back() == ' ') collapsed.pop_back();
  return collapsed;
}

constexpr bool kLittleEndianHost = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

}  // namespace

std::string ProgramVersion() { return GRANASYM_PROGRAM_VERSION; }

std::string ResultsKey() {
  std::string isa;
#if defined(__x86_64__)
  isa = "x86_64";
#elif defined(__aarch64__)
  isa = "aarch64";
#else
  isa = "other";
#endif
#ifdef __AVX__
  isa += " avx";
#endif
#ifdef __AVX2__
  isa += " avx2";
#endif
#ifdef __FMA__
  isa += " fma";
#endif
#ifdef __AVX512F__
  isa += " avx512f";
#endif
#if defined(__clang__)
  const std::string compiler = "Clang " __clang_version__;
#elif defined(__GNUC__)
  const std::string compiler = "GNU " __VERSION__;
#else
  const std::string compiler = "unknown compiler";
#endif
  return "results v" + std::to_string(kResultsVersion) + "; " + compiler + "; " +
         GRANASYM_BUILD_TYPE + "; " + isa;
}

std::string HostCpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    // "model name\t: Intel(R) Xeon(R) ..."
    if (line.compare(0, 10, "model name") != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string model = CollapseBlanks(line.substr(colon + 1));
    if (!model.empty()) return model;
  }
  utsname host{};
  if (uname(&host) == 0 && host.machine[0] != '\0') return CollapseBlanks(host.machine);
  return "unknown";
}

std::string Sha256Hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1) {
    Fail("EVP_Digest");
  }
  return Hex(digest, size);
}

void Sha256::ContextDeleter::operator()(evp_md_ctx_st* context) const { EVP_MD_CTX_free(context); }

Sha256::Sha256() : context_(EVP_MD_CTX_new()) {
  if (!context_) Fail("EVP_MD_CTX_new");
  if (EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1) Fail("EVP_DigestInit_ex");
}

Sha256::Sha256(Sha256&& other) noexcept = default;
Sha256& Sha256::operator=(Sha256&& other) noexcept = default;
Sha256::~Sha256() = default;

void Sha256::Update(const void* data, size_t size) {
  GRANASYM_CHECK(context_) << "Sha256::Update on a moved-from hash";
  if (size == 0) return;
  if (EVP_DigestUpdate(context_.get(), data, size) != 1) Fail("EVP_DigestUpdate");
}

void Sha256::UpdateLittleEndian(const void* data, size_t count, size_t scalar_size) {
  if (kLittleEndianHost || scalar_size == 1) {
    Update(data, count * scalar_size);
    return;
  }
  // Big-endian host: reverse each scalar's bytes, a block at a time.
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  unsigned char block[4096];
  const size_t per_block = sizeof(block) / scalar_size;
  for (size_t first = 0; first < count; first += per_block) {
    const size_t n = std::min(per_block, count - first);
    for (size_t k = 0; k < n; ++k) {
      const unsigned char* scalar = bytes + (first + k) * scalar_size;
      std::reverse_copy(scalar, scalar + scalar_size, block + k * scalar_size);
    }
    Update(block, n * scalar_size);
  }
}

std::string Sha256::HexDigest() const {
  GRANASYM_CHECK(context_) << "Sha256::HexDigest on a moved-from hash";
  // Finalise a copy, so that the running hash can continue.
  std::unique_ptr<evp_md_ctx_st, ContextDeleter> copy(EVP_MD_CTX_new());
  if (!copy) Fail("EVP_MD_CTX_new");
  if (EVP_MD_CTX_copy_ex(copy.get(), context_.get()) != 1) Fail("EVP_MD_CTX_copy_ex");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(copy.get(), digest, &size) != 1) Fail("EVP_DigestFinal_ex");
  return Hex(digest, size);
}

int HardwareThreads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace granasym
