#pragma once
// SHA-256 (FIPS 180-4, unchanged from FIPS 180-2) for content addresses:
// a job's id is the hash of its canonical scene, a study's the hash of its
// canonical document. Written here to avoid a crypto dependency for ids.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace railvsi::scheduler {

class Sha256 {
 public:
  // kAuto uses the CPU's SHA instructions (x86 SHA extensions) when it has
  // them, else the portable code; kPortable always the portable code (the
  // tests compare the two). Both give the same digest.
  enum class Engine { kAuto, kPortable };
  explicit Sha256(Engine engine = Engine::kAuto);
  // Whether kAuto uses the CPU's SHA instructions on this machine.
  static bool cpu_instructions();
  Sha256& update(std::string_view bytes);
  Sha256& update(const void* data, std::size_t size);
  // The digest; the object must not be updated afterwards.
  std::array<std::uint8_t, 32> digest();
  std::string hex_digest();  // 64 lower-case hex digits

 private:
  void compress(const std::uint8_t* block);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
  bool use_cpu_ = false;
};

std::string sha256_hex(std::string_view bytes);

}  // namespace railvsi::scheduler
