#include "io/input_file.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

std::uintmax_t check_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes,
                                const std::string& json_path) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(json_path, "cannot open the file for reading: it does not exist", file.string());
  if (!std::filesystem::is_regular_file(status))
    throw InputError(json_path, "not a regular file (a device, a FIFO or a directory cannot be an input)",
                     file.string());
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) throw InputError(json_path, "cannot read the size of the file: " + ec.message(), file.string());
  if (size > max_bytes)
    throw InputError(json_path,
                     fmt::format("the file has {} bytes, more than the {} allowed for this kind of input", size,
                                 max_bytes),
                     file.string());
  return size;
}

}  // namespace railvsi
