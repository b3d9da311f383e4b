#include "solver/nearest_eigenpairs.hpp"

#include "solver/block_lanczos.hpp"
#include "solver/spectra_lanczos.hpp"

namespace railvsi {

std::unique_ptr<NearestEigenpairs> make_nearest_eigenpairs(const ModalOptions& options) {
  if (options.lanczos_block > 1) return std::make_unique<BlockLanczos>(options);
  return std::make_unique<SpectraLanczos>(options);
}

}  // namespace railvsi
