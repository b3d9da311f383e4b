#pragma once
// Opening an input file safely: only a regular file (not /dev/zero, a FIFO
// or a directory, which would be read without end or block) and not larger
// than a limit for its kind, checked before a byte is read.
#include <cstdint>
#include <filesystem>
#include <string>

namespace railvsi {

// Size limits per kind of input file (bytes).
inline constexpr std::uintmax_t kMaxJsonFileBytes = 64ull << 20;      // scenes, studies, trains, maps
inline constexpr std::uintmax_t kMaxTableFileBytes = 256ull << 20;    // irregularity profiles
inline constexpr std::uintmax_t kMaxMatrixFileBytes = 16ull << 30;    // Matrix Market structure matrices

// Throws InputError(json_path, ..., file) unless `file` is a regular file
// of at most max_bytes; returns its size.
std::uintmax_t check_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes,
                                const std::string& json_path = "/");

}  // namespace railvsi
