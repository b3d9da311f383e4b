// The mode solver (modal_analysis: shift-invert Lanczos on spectrum slices)
// side by side with SciPy's eigsh in shift-invert mode (ARPACK on SuperLU,
// tests/bench/mode_solver_peer.py) on the same Matrix Market files, in one
// run: CPU seconds of each, their ratio, and the largest relative
// difference of their frequencies. Both at the same first shift (-1) and
// tolerance (1e-10). By hand, with OPENBLAS_NUM_THREADS=1:
//   mode_solver_bench --matrices DIR [--modes 20,50,100,200]
//       DIR/K.mtx, DIR/M.mtx, e.g. from `vsi generate deck-3d`
//   mode_solver_bench --scene FILE.json [--cutoffs-hz 60,100,200]
//       a scene's structure, written to a temporary directory for the peer;
//       a cut-off asks every mode below it, the peer the same count
// Further options: --no-peer; --slice-modes N (ModalOptions::slice_modes);
// --block N (ModalOptions::lanczos_block: 1 single-vector Lanczos);
// --one-shift: also the two Lanczos libraries alone on one shift below the
// spectrum (exactly the modes asked, ncv = 2 k + 1, the same CHOLMOD L L'
// factor and tolerance): Spectra (what the slices run on) and ARPACK's
// dsaupd/dseupd in mode 3 (Debian's libarpack2-dev, when CMake found it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cpu_time.hpp"
#include "io/json_document.hpp"
#include "io/matrix_market.hpp"
#include "io/scene_loader.hpp"
#include "solver/modal_analysis.hpp"
#include "solver/shift_invert_factor.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include "../support/worst_of.hpp"

#ifdef RAILVSI_HAVE_ARPACK
// ARPACK-NG's C binding (arpack/arpack.h declares the complex routines with
// C's _Complex, which C++ refuses): the two real symmetric ones.
extern "C" {
void dsaupd_c(int* ido, char const* bmat, int n, char const* which, int nev, double tol, double* resid, int ncv,
              double* v, int ldv, int* iparam, int* ipntr, double* workd, double* workl, int lworkl, int* info);
void dseupd_c(int rvec, char const* howmny, int const* select, double* d, double* z, int ldz, double sigma,
              char const* bmat, int n, char const* which, int nev, double tol, double* resid, int ncv, double* v,
              int ldv, int* iparam, int* ipntr, double* workd, double* workl, int lworkl, int* info);
}
#endif

namespace {

using namespace railvsi;

constexpr double kShift = -1.0, kTolerance = 1e-10;

std::vector<double> numbers(const std::string& list) {
  std::vector<double> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

struct Peer {
  bool ran = false;
  double cpu_s = 0.0;
  std::vector<double> frequencies_hz;
};

Peer run_peer(const std::filesystem::path& dir, int modes) {
  const std::string command = std::string(RAILVSI_PYTHON) + " " + RAILVSI_MODE_SOLVER_PEER + " " + dir.string() +
                              " " + std::to_string(modes) + " " + std::to_string(kShift) + " " +
                              std::to_string(kTolerance);
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  Peer p;
  if (!pipe) return p;
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe.get())) out += buffer;
  try {
    const nlohmann::json j = nlohmann::json::parse(out);
    p.cpu_s = j["cpu_s"].get<double>();
    p.frequencies_hz = j["frequencies_hz"].get<std::vector<double>>();
    p.ran = true;
  } catch (const std::exception&) {
    std::fprintf(stderr, "the peer failed: %s\n", out.c_str());
  }
  return p;
}

struct Run {
  ModalResult result;
  double cpu_s = 0.0;
};

Run ours(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& o) {
  const double t = bench::process_cpu_s();
  Run r;
  r.result = modal_analysis(K, M, o);
  r.cpu_s = bench::process_cpu_s() - t;
  return r;
}

std::vector<double> to_hz(const std::vector<double>& lambda) {
  std::vector<double> hz;
  for (const double l : lambda) hz.push_back(std::sqrt(std::max(l, 0.0)) / (2.0 * M_PI));
  std::sort(hz.begin(), hz.end());
  return hz;
}

// Spectra's shift-invert solver alone on one shift (the solver before the
// slices, without its over-solve).
class FactorOp {
 public:
  using Scalar = double;
  explicit FactorOp(const ShiftInvertFactor& f) : f_(f) {}
  Eigen::Index rows() const { return f_.rows(); }
  Eigen::Index cols() const { return f_.rows(); }
  void set_shift(double) {}
  void perform_op(const double* x, double* y) const { f_.solve(x, y); }

 private:
  const ShiftInvertFactor& f_;
};

Run spectra_one_shift(const SparseMatrix& K, const SparseMatrix& M, int k) {
  const double t = bench::process_cpu_s();
  Run r;
  ShiftInvertFactor f(K, M);
  if (!f.factorize(kShift).ok()) return r;
  FactorOp op(f);
  Spectra::SparseSymMatProd<double> mass(M);
  Spectra::SymGEigsShiftSolver<FactorOp, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert> s(
      op, mass, k, std::min<Eigen::Index>(K.rows(), 2 * k + 1), kShift);
  s.init();
  s.compute(Spectra::SortRule::LargestMagn, 1000, kTolerance, Spectra::SortRule::SmallestAlge);
  if (s.info() == Spectra::CompInfo::Successful) {
    const Vector l = s.eigenvalues();
    r.result.frequencies_hz = to_hz(std::vector<double>(l.data(), l.data() + l.size()));
    [[maybe_unused]] const DenseMatrix phi = s.eigenvectors();  // the shapes too, as ARPACK and the product
  } else {
    r.result.status = {StatusCode::kNoConvergence, "Spectra did not converge"};
  }
  r.cpu_s = bench::process_cpu_s() - t;
  return r;
}

Run arpack_one_shift([[maybe_unused]] const SparseMatrix& K, [[maybe_unused]] const SparseMatrix& M,
                     [[maybe_unused]] int k) {
  Run r;
  r.result.status = {StatusCode::kInvalidInput, "not built with ARPACK"};
#ifdef RAILVSI_HAVE_ARPACK
  const double t = bench::process_cpu_s();
  ShiftInvertFactor f(K, M);
  if (!f.factorize(kShift).ok()) return r;
  const int n = static_cast<int>(K.rows());
  const int ncv = std::min(n, 2 * k + 1);
  const int lworkl = ncv * (ncv + 8);
  std::vector<double> resid(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n) * ncv),
      workd(3 * static_cast<std::size_t>(n)), workl(static_cast<std::size_t>(lworkl));
  int iparam[11] = {1, 0, 1000, 1, 0, 0, 3, 0, 0, 0, 0}, ipntr[11] = {}, ido = 0, info = 0;
  Vector tmp(n);
  for (;;) {
    dsaupd_c(&ido, "G", n, "LM", k, kTolerance, resid.data(), ncv, v.data(), n, iparam, ipntr, workd.data(),
             workl.data(), lworkl, &info);
    double* x = workd.data() + ipntr[0] - 1;
    double* y = workd.data() + ipntr[1] - 1;
    if (ido == -1) {  // y = (K - sigma M)^-1 M x
      tmp = M * Eigen::Map<const Vector>(x, n);
      f.solve(tmp.data(), y);
    } else if (ido == 1) {  // M x given
      f.solve(workd.data() + ipntr[2] - 1, y);
    } else if (ido == 2) {
      Eigen::Map<Vector>(y, n) = M * Eigen::Map<const Vector>(x, n);
    } else {
      break;
    }
  }
  if (info < 0) return r;
  std::vector<int> select(static_cast<std::size_t>(ncv));
  std::vector<double> d(static_cast<std::size_t>(k)), z(static_cast<std::size_t>(n) * k);
  dseupd_c(1, "A", select.data(), d.data(), z.data(), n, kShift, "G", n, "LM", k, kTolerance, resid.data(), ncv,
           v.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl, &info);
  if (info == 0 && iparam[4] >= k) {
    r.result.status = Status::Ok();
    r.result.frequencies_hz = to_hz(d);
  }
  r.cpu_s = bench::process_cpu_s() - t;
#endif
  return r;
}

double worst_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return NAN;
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (b[k] > 0.0) worst = railvsi::testing::worst_of(worst, std::abs(a[k] - b[k]) / b[k]);
  return worst;
}

struct OneShift {
  Run spectra, arpack;
};

void row(const std::string& label, Eigen::Index n, const Run& r, const OneShift* one_shift, const Peer& peer) {
  const auto count = static_cast<int>(r.result.frequencies_hz.size());
  std::printf("%-12s %8ld %6d %9.2f %7d", label.c_str(), static_cast<long>(n), count, r.cpu_s,
              r.result.factorizations);
  if (!r.result.status.ok()) std::printf("  FAILED: %s", r.result.status.message().c_str());
  if (one_shift)
    for (const Run* o : {&one_shift->spectra, &one_shift->arpack})
      std::printf(" %10.2f%s", o->cpu_s, o->result.status.ok() ? "" : "(failed)");
  if (peer.ran)
    std::printf(" %9.2f %7.3f %10.1e", peer.cpu_s, r.cpu_s / peer.cpu_s,
                worst_difference(r.result.frequencies_hz, peer.frequencies_hz));
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string matrices, scene_file;
  std::vector<double> modes{20, 50, 100, 200}, cutoffs_hz;
  bool peer = true, one_shift = false;
  int slice_modes = ModalOptions{}.slice_modes;
  int block = ModalOptions{}.lanczos_block;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--matrices") matrices = value();
    else if (a == "--scene") scene_file = value();
    else if (a == "--modes") modes = numbers(value());
    else if (a == "--cutoffs-hz") cutoffs_hz = numbers(value());
    else if (a == "--slice-modes") slice_modes = std::stoi(value());
    else if (a == "--block") block = std::stoi(value());
    else if (a == "--no-peer") peer = false;
    else if (a == "--one-shift") one_shift = true;
    else {
      std::fprintf(stderr, "usage: mode_solver_bench (--matrices DIR | --scene FILE) [--modes LIST] "
                           "[--cutoffs-hz LIST] [--slice-modes N] [--block N] [--no-peer] [--one-shift]\n");
      return 2;
    }
  }
  SparseMatrix K, M;
  std::filesystem::path dir = matrices;
  if (!scene_file.empty()) {
    const Scene scene = parse_scene(read_json_file(scene_file), std::filesystem::path(scene_file).parent_path(),
                                    scene_file);
    K = scene.structure->K();
    M = scene.structure->M();
    dir = std::filesystem::temp_directory_path() / ("mode_solver_bench_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    write_matrix_market(dir / "K.mtx", K);
    write_matrix_market(dir / "M.mtx", M);
    if (modes.size() == 4 && cutoffs_hz.empty()) cutoffs_hz = {60, 100, 200};
    if (!cutoffs_hz.empty()) modes.clear();
  } else if (!matrices.empty()) {
    K = read_matrix_market(dir / "K.mtx", "K");
    M = read_matrix_market(dir / "M.mtx", "M");
  } else {
    std::fprintf(stderr, "--matrices DIR or --scene FILE\n");
    return 2;
  }
  std::printf("%-12s %8s %6s %9s %7s%s%s\n", "case", "DOFs", "modes", "ours_s", "factors",
              one_shift ? " spectra1_s  arpack1_s" : "", peer ? "   scipy_s   ratio  max_df/f" : "");
  ModalOptions base;
  base.slice_modes = slice_modes;
  base.lanczos_block = block;
  const auto one = [&](int count) { return OneShift{spectra_one_shift(K, M, count), arpack_one_shift(K, M, count)}; };
  for (const double k : modes) {
    ModalOptions o = base;
    o.modes = static_cast<int>(k);
    const Run r = ours(K, M, o);
    const OneShift single = one_shift ? one(o.modes) : OneShift{};
    const Peer p = peer ? run_peer(dir, o.modes) : Peer{};
    row(std::to_string(o.modes) + " modes", K.rows(), r, one_shift ? &single : nullptr, p);
  }
  for (const double f : cutoffs_hz) {
    ModalOptions o = base;
    o.modes = 0;
    o.max_frequency_hz = f;
    const Run r = ours(K, M, o);
    const auto count = static_cast<int>(r.result.frequencies_hz.size());
    const OneShift single = one_shift ? one(count) : OneShift{};
    const Peer p = peer && count > 0 ? run_peer(dir, count) : Peer{};
    char label[32];
    std::snprintf(label, sizeof label, "to %.0f Hz", f);
    row(label, K.rows(), r, one_shift ? &single : nullptr, p);
  }
  if (!scene_file.empty()) std::filesystem::remove_all(dir);
  return 0;
}
