#include "analysis/modal_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/sampled_peak.hpp"
#include "simulation/run_monitor.hpp"

namespace railvsi {

ModalSweep::ModalSweep(const ModalBasis& basis, const Train& train, const std::vector<int>& rail_lines, double dt_s,
                       std::shared_ptr<const ModalSectionForces> sections, DeckOutputCorrection correction)
    : basis_(basis), n_modes_(basis.num_modes()), correction_(correction), dt_s_(dt_s), sections_(std::move(sections)) {
  u_limit_m_ = implausible_displacement_m(basis.structure());
  n_forms_ = sections_ ? sections_->num_forms() : 0;
  if (correction_ == DeckOutputCorrection::kStatic) n_corrected_ = static_cast<int>(basis.structure().outputs().size());
  width_ = n_modes_ + n_forms_ + 2 * n_corrected_;
  groups_ = (static_cast<std::size_t>(width_) + kColumnGroup - 1) / kColumnGroup;
  for (double w : basis.omega_rad_s()) inverse_omega2_.push_back(1.0 / (w * w));
  if (!train.is_moving_forces()) throw InputError("/train", "the modal moving-force rung needs a train of moving forces");
  if (rail_lines.empty()) throw InputError("/analysis/contact/rail_lines", "no rail line to load");
  for (int k = 0; k < n_modes_; ++k)
    steps_.push_back(make_modal_step(basis.omega_rad_s()[static_cast<std::size_t>(k)],
                                     basis.zeta()[static_cast<std::size_t>(k)], dt_s));
  share_ = 1.0 / static_cast<double>(rail_lines.size());
  std::vector<MovingForce> axles = train.moving_forces;
  std::stable_sort(axles.begin(), axles.end(),
                   [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; });
  for (const MovingForce& m : axles) {
    offsets_.push_back(m.offset_m);
    loads_N_.push_back(m.load_N);
  }
  const StructureModel& s = basis.structure();
  const auto n = static_cast<std::size_t>(n_modes_);
  const auto width = static_cast<std::size_t>(width_);
  // The cubic through the values at four interior points of an element
  // (xi = 1/8, 3/8, 5/8, 7/8): exact for the cubic a form's unit value is
  // there, and blind to the node where a shear cut may exclude a load.
  const std::array<double, 4> xi_fit{0.125, 0.375, 0.625, 0.875};
  Eigen::Matrix4d vandermonde;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) vandermonde(i, j) = std::pow(xi_fit[static_cast<std::size_t>(i)], j);
  const Eigen::Matrix4d fit = vandermonde.inverse();
  // The residual flexibility of the outputs, by rail DOF.
  const DenseMatrix* residual = n_corrected_ > 0 ? &basis.output_residual_flexibility() : nullptr;
  std::vector<int> rail_index;
  if (residual) {
    rail_index.assign(static_cast<std::size_t>(s.num_dofs()), -1);
    for (std::size_t i = 0; i < s.rail_dofs().size(); ++i)
      rail_index[static_cast<std::size_t>(s.rail_dofs()[i])] = static_cast<int>(i);
  }
  const auto hermite = [&](const double phi[4], double h, double* c) {
    // Hermite: N1 = 1 - 3xi^2 + 2xi^3, N2 = h(xi - 2xi^2 + xi^3),
    // N3 = 3xi^2 - 2xi^3, N4 = h(xi^3 - xi^2), collected by powers of xi.
    const double f = -share_;  // downward force, shared between the rails
    c[0] = f * phi[0];
    c[1] = f * h * phi[1];
    c[2] = f * (-3.0 * phi[0] - 2.0 * h * phi[1] + 3.0 * phi[2] - h * phi[3]);
    c[3] = f * (2.0 * phi[0] + h * phi[1] - 2.0 * phi[2] + h * phi[3]);
  };
  for (int r : rail_lines) {
    if (r < 0 || r >= static_cast<int>(s.rails().size()))
      throw InputError("/analysis/contact/rail_lines", fmt::format("the structure has no rail line {}", r));
    const RailLine& line = s.rails()[static_cast<std::size_t>(r)];
    Rail rail;
    rail.line = r;
    rail.x_m = line.x_m;
    rail.start_m = line.start_m();
    rail.end_m = line.end_m();
    rail.cubic.assign(line.num_elements() * width * 4, 0.0);
    for (std::size_t e = 0; e < line.num_elements(); ++e) {
      const double h = line.x_m[e + 1] - line.x_m[e];
      for (std::size_t k = 0; k < n; ++k) {
        // End values (v_i, theta_i, v_j, theta_j) of mode k; a fixed DOF is 0.
        double phi[4];
        for (std::size_t j = 0; j < 4; ++j) {
          const int dof = line.element_dofs[e][j];
          phi[j] = dof < 0 ? 0.0 : basis.row(dof)[k];
        }
        hermite(phi, h, rail.cubic.data() + (e * width + k) * 4);
      }
      for (int i = 0; i < n_corrected_; ++i) {
        // Output i's residual displacement under the axle, and its second
        // derivative in x: (2 c2 + 6 c3 xi) / h^2.
        double ends[4];
        for (std::size_t j = 0; j < 4; ++j) {
          const int dof = line.element_dofs[e][j];
          const int at = dof < 0 ? -1 : rail_index[static_cast<std::size_t>(dof)];
          ends[j] = at < 0 ? 0.0 : (*residual)(i, at);
        }
        const std::size_t column = n + static_cast<std::size_t>(n_forms_ + i);
        double* c = rail.cubic.data() + (e * width + column) * 4;
        hermite(ends, h, c);
        double* c2 = rail.cubic.data() + (e * width + column + static_cast<std::size_t>(n_corrected_)) * 4;
        c2[0] = 2.0 * c[2] / (h * h);
        c2[1] = 6.0 * c[3] / (h * h);
        c2[2] = c2[3] = 0.0;
      }
      for (int form = 0; sections_ && form < sections_->num_forms(); ++form) {
        Eigen::Vector4d values;
        for (int i = 0; i < 4; ++i)
          values[i] = share_ * sections_->statics().unit_form_value(form, r, line.x_m[e] + xi_fit[static_cast<std::size_t>(i)] * h);
        const Eigen::Vector4d coef = fit * values;
        double* c = rail.cubic.data() + (e * width + n + static_cast<std::size_t>(form)) * 4;
        for (int j = 0; j < 4; ++j) c[j] = coef[j];
      }
    }
    tabulate_train_load(rail);
    rails_.push_back(std::move(rail));
  }
  if (sections_) {
    // Forms the envelope reads signed (support reactions) and as |value|.
    const SectionForms& forms = sections_->forms();
    std::vector<bool> as_abs(forms.forms.size(), false);
    form_signed_.assign(forms.forms.size(), false);
    const auto mark = [](std::vector<bool>& used, int f) {
      if (f >= 0) used[static_cast<std::size_t>(f)] = true;
    };
    for (const SectionForms::Point& point : forms.points)
      for (int f : {point.moment_left, point.moment_right, point.shear_left, point.shear_right}) mark(as_abs, f);
    for (const SectionForms::Support& support : forms.supports) {
      mark(form_signed_, support.reaction);
      for (int f : support.rotations) mark(as_abs, f);
    }
    forms_fold_ = true;
    for (std::size_t f = 0; f < as_abs.size(); ++f) forms_fold_ = forms_fold_ && !(as_abs[f] && form_signed_[f]);
    // Where an axle crosses a form's section or support, or a rail end: as
    // the rail's node there (the bits of the train-load table's breakpoint,
    // so that the two sides of the kink are the table's two pieces).
    std::vector<double> at_m;
    for (const Rail& rail : rails_) {
      at_m.push_back(rail.start_m);
      at_m.push_back(rail.end_m);
      for (const LinearForm& form : forms.forms) {
        const auto node = std::lower_bound(rail.x_m.begin(), rail.x_m.end(), form.x_m);
        double nearest = form.x_m;
        for (auto it : {node, node == rail.x_m.begin() ? node : node - 1})
          if (it != rail.x_m.end() && std::abs(*it - form.x_m) < std::abs(nearest - form.x_m) + 1e-9) nearest = *it;
        at_m.push_back(nearest);
      }
    }
    std::sort(at_m.begin(), at_m.end());
    at_m.erase(std::unique(at_m.begin(), at_m.end()), at_m.end());
    for (double offset : offsets_)
      for (double x : at_m) kinks_m_.push_back(x + offset);
    std::sort(kinks_m_.begin(), kinks_m_.end());
    kinks_m_.erase(std::unique(kinks_m_.begin(), kinks_m_.end()), kinks_m_.end());
  }
  twist_ = make_deck_twist_gauge(s, rail_lines);
  if (twist_.available()) {
    twist_modes_ = DenseMatrix::Zero(static_cast<Eigen::Index>(twist_.forms.size()), n_modes_);
    for (std::size_t b = 0; b < twist_.forms.size(); ++b)
      for (const auto& [index, coef] : twist_.forms[b]) {
        const double* phi = basis.row(twist_.dofs[static_cast<std::size_t>(index)]);
        for (int k = 0; k < n_modes_; ++k) twist_modes_(static_cast<Eigen::Index>(b), k) += coef * phi[k];
      }
  }
}

void ModalSweep::tabulate_train_load(Rail& rail) const {
  const auto width = static_cast<std::size_t>(width_);
  std::vector<double>& b = rail.breaks;
  b.clear();
  b.reserve(rail.x_m.size() * offsets_.size());
  for (double offset : offsets_)
    for (double node : rail.x_m) b.push_back(node + offset);
  std::sort(b.begin(), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  const std::size_t n_pieces = b.size() - 1;
  rail.pieces.assign(n_pieces * groups_ * kColumnGroup * 4, 0.0);
  for (std::size_t i = 0; i < n_pieces; ++i) {
    // Inside the piece no axle is on a node: its midpoint places them all.
    const double mid = 0.5 * (b[i] + b[i + 1]);
    for (std::size_t a = 0; a < offsets_.size(); ++a) {
      const double xa = mid - offsets_[a];
      if (!(xa > rail.start_m && xa < rail.end_m)) continue;
      const auto above = std::upper_bound(rail.x_m.begin(), rail.x_m.end(), xa);
      const auto e = static_cast<std::size_t>(above - rail.x_m.begin()) - 1;
      // xi = alpha + beta u on this piece: the axle's cubic in xi, shifted
      // to the piece's start and scaled to u (Taylor at alpha).
      const double h = rail.x_m[e + 1] - rail.x_m[e];
      const double alpha = (b[i] - offsets_[a] - rail.x_m[e]) / h, beta = 1.0 / h;
      const double load = loads_N_[a];
      const double* c = rail.cubic.data() + e * width * 4;
      for (std::size_t k = 0; k < width; ++k, c += 4) {
        rail.pieces[piece_index(i, k, 0)] += load * (((c[3] * alpha + c[2]) * alpha + c[1]) * alpha + c[0]);
        rail.pieces[piece_index(i, k, 1)] += load * ((3.0 * c[3] * alpha + 2.0 * c[2]) * alpha + c[1]) * beta;
        rail.pieces[piece_index(i, k, 2)] += load * (3.0 * c[3] * alpha + c[2]) * beta * beta;
        rail.pieces[piece_index(i, k, 3)] += load * c[3] * beta * beta * beta;
      }
    }
  }
}

void ModalSweep::modal_load(double x, double* p, std::size_t stride, std::size_t* piece,
                            ModalSweepWorkspace& ws) const {
  const auto width = static_cast<std::size_t>(width_);
  for (std::size_t k = 0; k < width; ++k) p[k * stride] = 0.0;
  for (std::size_t r = 0; r < rails_.size(); ++r) {
    const Rail& rail = rails_[r];
    const std::vector<double>& b = rail.breaks;
    // Before the first breakpoint no axle has reached the rail; past the
    // last every axle has left it.
    if (b.size() < 2 || x < b.front() || x > b.back()) continue;
    std::size_t& i = piece[r * stride];
    while (i + 2 < b.size() && x >= b[i + 1]) ++i;
    const double u = x - b[i];
    if (u == 0.0 || x == b.back()) {
      add_axle_loads(rail, x, p, stride, ws);
      continue;
    }
    piece_load(rail, i, u, p, stride, false);
  }
}

void ModalSweep::table_columns_at(double s, bool left, double* columns) const {
  for (const Rail& rail : rails_) {
    const std::vector<double>& b = rail.breaks;
    if (b.size() < 2 || (left ? (s <= b.front() || s > b.back()) : (s < b.front() || s >= b.back()))) continue;
    // left: b[i] < s <= b[i + 1]; from above: b[i] <= s < b[i + 1].
    const auto at = left ? std::lower_bound(b.begin(), b.end(), s) : std::upper_bound(b.begin(), b.end(), s);
    const auto i = static_cast<std::size_t>(at - b.begin()) - 1;
    piece_load(rail, i, s - b[i], columns, 1, false);
  }
}

void ModalSweep::piece_load(const Rail& rail, std::size_t i, double u, double* p, std::size_t stride,
                            bool assign) const {
  const auto width = static_cast<std::size_t>(width_);
  const double* d = rail.pieces.data() + piece_index(i, 0, 0);
  constexpr std::size_t g = kColumnGroup;  // from one power to the next
  for (std::size_t k0 = 0; k0 < width; k0 += g, d += 4 * g) {
    const std::size_t in_group = std::min(g, width - k0);
    for (std::size_t j = 0; j < in_group; ++j) {
      const double v = ((d[3 * g + j] * u + d[2 * g + j]) * u + d[g + j]) * u + d[j];
      double& to = p[(k0 + j) * stride];
      to = assign ? v : to + v;
    }
  }
}

void ModalSweep::add_axle_loads(const Rail& rail, double x, double* p, std::size_t stride,
                                ModalSweepWorkspace& ws) const {
  const auto n = static_cast<std::size_t>(n_modes_);
  const auto width = static_cast<std::size_t>(width_);
  const std::size_t nodes = rail.x_m.size();
  for (std::size_t a = 0; a < offsets_.size(); ++a) {
    const double xa = x - offsets_[a];
    if (!(xa >= rail.start_m && xa <= rail.end_m)) continue;  // as RailLine::covers
    // The element whose nodes bracket xa (the last one at the end), as RailLine::locate.
    const auto above = std::upper_bound(rail.x_m.begin(), rail.x_m.end(), xa);
    const std::size_t i = std::min(static_cast<std::size_t>(above - rail.x_m.begin()), nodes - 1) - 1;
    const double xi = (xa - rail.x_m[i]) / (rail.x_m[i + 1] - rail.x_m[i]);
    const double load = loads_N_[a];
    const double* c = rail.cubic.data() + i * width * 4;
    // On a node the forms are evaluated exactly (a shear cut there may
    // exclude the load); inside an element, by their cubics.
    const bool exact_forms = sections_ && xi == 0.0;
    const std::size_t forms_end = n + static_cast<std::size_t>(n_forms_);
    for (std::size_t k = 0; k < width; ++k, c += 4) {
      if (exact_forms && k >= n && k < forms_end) continue;
      p[k * stride] += load * (((c[3] * xi + c[2]) * xi + c[1]) * xi + c[0]);
    }
    if (exact_forms) {
      std::fill(ws.form_values.begin(), ws.form_values.end(), 0.0);
      sections_->statics().add_form_values(rail.line, xa, share_ * load, ws.form_values);
      for (std::size_t f = 0; f < ws.form_values.size(); ++f) p[(n + f) * stride] += ws.form_values[f];
    }
  }
}

namespace {

// The lanes of a group as one value: a double for one lane, a vector of
// four doubles (GCC's vector extension: element-wise IEEE arithmetic, the
// same bits as four scalars) for four.
template <int L>
struct LaneValue {
  using type = double;
};
template <>
struct LaneValue<4> {
  // Read and written in place in the workspace's doubles: no alignment
  // beyond a double's is assumed, and it may alias them.
  using type = double __attribute__((vector_size(4 * sizeof(double)), aligned(alignof(double)), may_alias));
};
static_assert(kSweepLanes == 4, "a group is one vector of four doubles");

template <class V>
[[gnu::always_inline]] inline double& lane_of(V& v, std::size_t l) {
  if constexpr (std::is_same_v<V, double>) return v;
  else return reinterpret_cast<double*>(&v)[l];
}
template <class V>
[[gnu::always_inline]] inline double lane_of(const V& v, std::size_t l) {
  if constexpr (std::is_same_v<V, double>) return v;
  else return reinterpret_cast<const double*>(&v)[l];
}

// max(m, |x|) as std::max(m, std::abs(x)) for each lane: (m < |x|) ? |x| : m.
template <class V>
[[gnu::always_inline]] inline void raise_max_abs(V& m, const V& x) {
  if constexpr (std::is_same_v<V, double>) {
    m = std::max(m, std::abs(x));
  } else {
    const V ax = x < 0.0 ? -x : x;  // |-0.0| = -0.0 here, which max never keeps over 0.0
    m = m < ax ? ax : m;
  }
}

// What a chunk of steps may hold between its samples, per signal and lane:
// the largest |sample| and |difference of two consecutive samples| of this
// chunk and of the one before (whose last two samples start the chunk's
// window), and the last sample. A parabola's vertex through samples below
// h apart with middle |sample| y1 above both neighbours' rises at most
// |y2 - y0| / 8 <= h / 4 above y1 (its curvature |a| >= |b|, the vertex
// y1 + b^2 / (4 |a|)), so a chunk whose largest |sample| + h / 4 stays
// below the largest |value| so far holds no vertex that can raise the
// peak and need not be refined.
template <int L>
class ChunkBounds {
  using V = typename LaneValue<L>::type;

 public:
  explicit ChunkBounds(std::size_t signals) : n_(signals), values_(5 * signals * sizeof(V) / sizeof(double), 0.0) {}
  [[gnu::always_inline]] void sample(std::size_t j, const V& v) {
    raise_max_abs(at(kMax)[j], v);
    raise_max_abs(at(kStep)[j], v - at(kLast)[j]);
    at(kLast)[j] = v;
  }
  bool may_beat(std::size_t j, std::size_t lane, double largest) const {
    const double h = std::max(lane_of(at(kStep)[j], lane), lane_of(at(kBeforeStep)[j], lane));
    const double top = std::max(lane_of(at(kMax)[j], lane), lane_of(at(kBeforeMax)[j], lane)) + 0.25 * h;
    return !(top * (1.0 + 1e-12) < largest);
  }
  // This chunk becomes the one before the next.
  void next_chunk() {
    for (std::size_t j = 0; j < n_; ++j) {
      at(kBeforeMax)[j] = at(kMax)[j];
      at(kBeforeStep)[j] = at(kStep)[j];
      at(kMax)[j] = at(kStep)[j] = V{};
    }
  }

 private:
  enum Row : std::size_t { kMax, kStep, kBeforeMax, kBeforeStep, kLast };
  V* at(Row r) { return reinterpret_cast<V*>(values_.data()) + r * n_; }
  const V* at(Row r) const { return reinterpret_cast<const V*>(values_.data()) + r * n_; }
  std::size_t n_;
  std::vector<double> values_;
};

}  // namespace

template <int L>
[[gnu::always_inline]] inline void ModalSweep::run_lanes(const SweepLane* lanes, int count, ModalSweepRun* out, ModalSweepWorkspace& ws,
                           Histories* histories, int history_stride, LaneCode code) const {
  using V = typename LaneValue<L>::type;
  static_assert(kColumnGroup == 4, "a group of columns is one vector of four doubles");
  using Columns = LaneValue<4>::type;  // a group of columns of the train-load table
  constexpr auto lanes_n = static_cast<std::size_t>(L);
  const auto n = static_cast<std::size_t>(n_modes_);
  const auto width = static_cast<std::size_t>(width_);
  // The loads' columns padded to whole groups of the train-load table
  // (the padding's coefficients are 0: it holds 0 and is never read).
  const std::size_t padded_width = groups_ * kColumnGroup;
  ws.p.assign(padded_width * lanes_n, 0.0);
  for (auto* v : {&ws.q, &ws.qd, &ws.qdd}) v->assign(n * lanes_n, 0.0);
  const auto n_forms = static_cast<std::size_t>(n_forms_);
  ws.lane_values.assign(n_forms * lanes_n, 0.0);
  ws.form_values.assign(sections_ ? static_cast<std::size_t>(sections_->num_forms()) : 0, 0.0);
  ws.piece.assign(rails_.size() * lanes_n, 0);
  ws.offset.assign(rails_.size() * lanes_n, 0.0);
  const StructureModel& s = basis_.structure();
  const DenseMatrix& Phi_out = basis_.at_outputs();
  const std::size_t np = s.outputs().size();
  // Idle lanes (l >= count) repeat lane 0 and record nothing.
  std::array<SweepLane, L> lane;
  std::array<long, L> last_step{};  // a lane records steps 0..last_step
  long steps = 0;
  for (int l = 0; l < L; ++l) {
    lane[static_cast<std::size_t>(l)] = lanes[l < count ? l : 0];
    last_step[static_cast<std::size_t>(l)] = l < count ? lanes[l].n_steps : -1;
    steps = std::max(steps, last_step[static_cast<std::size_t>(l)]);
  }
  // The largest samples of every lane as vectors (an idle lane's are never
  // read); refined between samples at the end.
  std::vector<double> maxima(2 * np * lanes_n, 0.0);
  V* max_u = reinterpret_cast<V*>(maxima.data());
  V* max_a = max_u + np;
  for (int l = 0; l < count; ++l) {
    ModalSweepRun& o = out[l];  // freshly made by the caller
    if (sections_) o.sections.emplace(sections_->forms());
    if (twist_.available()) o.max_abs_twist_m = 0.0;
    for (auto* kept : {&ws.displacement[static_cast<std::size_t>(l)], &ws.acceleration[static_cast<std::size_t>(l)]}) {
      kept->resize(np);
      for (auto& k : *kept) k.resize(static_cast<std::size_t>(lanes[l].n_steps) + 1);
    }
    ws.kink_splits[static_cast<std::size_t>(l)].clear();
  }
  // The forms' samples of a chunk of steps: sample `step` of lane l and
  // form f at window_of[f * L + l][step - window_base]; an idle lane's go
  // to a row never read. Refined at the end of each chunk (refine_window).
  constexpr long kChunkSteps = 64;
  constexpr auto kWindow = static_cast<std::size_t>(kChunkSteps) + 2;
  ws.form_window.assign((n_forms * lanes_n + 1) * kWindow, 0.0);
  std::vector<double*> window_of(n_forms * lanes_n, ws.form_window.data() + n_forms * lanes_n * kWindow);
  for (std::size_t f = 0; f < n_forms; ++f)
    for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l)
      window_of[f * lanes_n + l] = ws.form_window.data() + (l * n_forms + f) * kWindow;
  long window_base = -1;  // the sample at the window's start
  ChunkBounds<L> form_bounds(n_forms);
  const int stride = std::max(1, history_stride);
  if (histories) {
    Histories& h = *histories;
    h.point_names.clear();
    for (const OutputPoint& o : s.outputs()) h.point_names.push_back(o.name);
    h.deck_displacement_m.assign(np, {});
    h.deck_acceleration_mps2.assign(np, {});
    const auto samples = static_cast<std::size_t>(lanes[0].n_steps / stride + 2);
    h.t_s.reserve(samples);
    for (std::size_t i = 0; i < np; ++i) {
      h.deck_displacement_m[i].reserve(samples);
      h.deck_acceleration_mps2[i].reserve(samples);
    }
  }
  // The lanes' loads (width columns) and modal state (n modes), one V each.
  static_assert(sizeof(V) == lanes_n * sizeof(double));
  V* p = reinterpret_cast<V*>(ws.p.data());
  V* q = reinterpret_cast<V*>(ws.q.data());
  V* qd = reinterpret_cast<V*>(ws.qd.data());
  V* qdd = reinterpret_cast<V*>(ws.qdd.data());
  const auto running = [&](long step, std::size_t l) { return step <= last_step[l]; };
  // The output and twist rows of the modes, each value in every lane
  // (loaded as vectors: no scalar broadcast in the loop).
  std::vector<double> rows_in_lanes((np + static_cast<std::size_t>(twist_modes_.rows())) * n * lanes_n);
  for (std::size_t i = 0; i < np + static_cast<std::size_t>(twist_modes_.rows()); ++i)
    for (std::size_t k = 0; k < n; ++k) {
      const auto row = static_cast<Eigen::Index>(i), col = static_cast<Eigen::Index>(k);
      const double v = i < np ? Phi_out(row, col) : twist_modes_(row - static_cast<Eigen::Index>(np), col);
      for (std::size_t l = 0; l < lanes_n; ++l) rows_in_lanes[(i * n + k) * lanes_n + l] = v;
    }
  const V* phi_rows = reinterpret_cast<const V*>(rows_in_lanes.data());
  // The section envelope takes the largest |value| of some forms and the
  // largest value of others over the steps: with each form's two maxima
  // kept over the run (every lane at once), it is updated once at the end
  // with the same result (a maximum is exact in any order).
  const bool fold_forms = sections_ && forms_fold_;
  std::vector<double> form_maxima(2 * n_forms * lanes_n, 0.0);
  V* max_abs_form = reinterpret_cast<V*>(form_maxima.data());
  V* max_form = max_abs_form + n_forms;
  for (std::size_t i = n_forms * lanes_n; i < form_maxima.size(); ++i)
    form_maxima[i] = -std::numeric_limits<double>::infinity();
  // Deck response at the output points from the modal coordinates of the
  // lanes still running at `step`; the maxima see every step, the
  // histories (lane 0 alone) every stride.
  // Every lane of the group records steps 0..all_until (until a lane
  // diverges, the shortest run's length).
  long all_until = steps;
  for (int l = 0; l < count; ++l) all_until = std::min(all_until, last_step[static_cast<std::size_t>(l)]);
  // Where each lane keeps the deck displacement and acceleration of each output point.
  std::vector<double*> displacement_of(np * lanes_n, nullptr), acceleration_of(np * lanes_n, nullptr);
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) {
      displacement_of[i * lanes_n + l] = ws.displacement[l][i].data();
      acceleration_of[i * lanes_n + l] = ws.acceleration[l][i].data();
    }
  // The deck's displacement and acceleration (2 i, 2 i + 1 of output i)
  // are refined chunk by chunk too, as the forms (refine_window below).
  ChunkBounds<L> deck_bounds(2 * np);
  const bool corrected = n_corrected_ > 0;
  const std::size_t corrected_u = n + n_forms;
  V speed2{};
  for (std::size_t l = 0; l < lanes_n; ++l) lane_of(speed2, l) = lane[l].speed_mps * lane[l].speed_mps;
  const auto record = [&](long step, double t, bool store) __attribute__((always_inline)) {
    const bool all = step <= all_until;
    if (store) histories->t_s.push_back(t);
    for (std::size_t i = 0; i < np; ++i) {
      V u{}, a{};

      for (std::size_t k = 0; k < n; ++k) {
        const V phi = phi_rows[i * n + k];
        u += phi * q[k];
        a += phi * qdd[k];
      }
      if (corrected) {
        // The modes left out, quasi-static: u + F r_i(x_a), a + v^2 F r_i''(x_a).
        u += p[corrected_u + i];
        a += speed2 * p[corrected_u + np + i];
      }
      deck_bounds.sample(2 * i, u);
      deck_bounds.sample(2 * i + 1, a);
      if (all) {
        raise_max_abs(max_u[i], u);
        raise_max_abs(max_a[i], a);
      } else {
        for (std::size_t l = 0; l < lanes_n; ++l) {
          if (!running(step, l)) continue;
          double& mu = lane_of(max_u[i], l);
          double& ma = lane_of(max_a[i], l);
          mu = std::max(mu, std::abs(lane_of(u, l)));
          ma = std::max(ma, std::abs(lane_of(a, l)));
        }
      }
      for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l)
        if (all || running(step, l)) {
          displacement_of[i * lanes_n + l][static_cast<std::size_t>(step)] = lane_of(u, l);
          acceleration_of[i * lanes_n + l][static_cast<std::size_t>(step)] = lane_of(a, l);
        }
      if (!store) continue;
      histories->deck_displacement_m[i].push_back(lane_of(u, 0));
      histories->deck_acceleration_mps2[i].push_back(lane_of(a, 0));
    }
    for (Eigen::Index b = 0; b < twist_modes_.rows(); ++b) {
      V t_b{};
      for (std::size_t k = 0; k < n; ++k) t_b += phi_rows[(np + static_cast<std::size_t>(b)) * n + k] * q[k];
      for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) {
        if (!running(step, l)) continue;
        ModalSweepRun& o = out[l];
        const double tl = lane_of(t_b, l);
        if (std::abs(tl) > *o.max_abs_twist_m || (step == 0 && b == 0)) {
          o.max_abs_twist_m = std::abs(tl);
          o.twist_x_m = twist_.x_m[static_cast<std::size_t>(b)];
        }
      }
    }
    if (!sections_) return;
    // The exact static value of each form under the loads (the columns of
    // p after the modes) plus the modes' dynamic part, every lane at once.
    const std::size_t nf = n_forms;
    V* values = reinterpret_cast<V*>(ws.lane_values.data());
    for (std::size_t f = 0; f < nf; ++f) values[f] = p[n + f];
    sections_->add_dynamic_part_of<V>(q, qd, qdd, p, values);
    if (!fold_forms) {
      for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) {
        if (!running(step, l)) continue;
        for (std::size_t f = 0; f < nf; ++f) ws.form_values[f] = lane_of(values[f], l);
        out[l].sections->update(ws.form_values);
      }
      return;
    }
    const auto at = static_cast<std::size_t>(step - window_base);
    for (std::size_t f = 0; f < nf; ++f) {
      // Every lane's (one that has ended writes what is never read).
      for (std::size_t l = 0; l < lanes_n; ++l) window_of[f * lanes_n + l][at] = lane_of(values[f], l);
      form_bounds.sample(f, values[f]);
      if (all) {
        raise_max_abs(max_abs_form[f], values[f]);
        max_form[f] = max_form[f] < values[f] ? values[f] : max_form[f];
        continue;
      }
      for (std::size_t l = 0; l < lanes_n; ++l) {
        if (!running(step, l)) continue;
        const double v = lane_of(values[f], l);
        lane_of(max_abs_form[f], l) = std::max(lane_of(max_abs_form[f], l), std::abs(v));
        lane_of(max_form[f], l) = std::max(lane_of(max_form[f], l), v);
      }
    }
  };

  // A form's influence line has a kink (a jump for a shear cut) where an
  // axle stands on its section or support: its peak over time may fall
  // between two steps, where the samples miss it and no parabola through
  // them follows it. So at each such instant the forms are evaluated too:
  // their static part exactly from the train-load table on both sides of
  // the kink, their dynamic part from the modes' state there, interpolated
  // within the step by the quintic Hermite polynomial through q, q', q'' at
  // both ends (exact values of the recurrence; error of order
  // (omega dt)^6 / 6! of a mode's amplitude), q'' from the equation of
  // motion under the load there. A lane's next kink: next_kink[l].
  const bool kinks = sections_ && !kinks_m_.empty();
  const auto lane_x = [&](std::size_t l, long step) {
    return lane[l].x0_m + lane[l].speed_mps * (static_cast<double>(step) * dt_s_);
  };
  std::array<std::size_t, L> next_kink{};
  if (kinks) {
    for (std::size_t l = 0; l < lanes_n; ++l)
      next_kink[l] = static_cast<std::size_t>(std::upper_bound(kinks_m_.begin(), kinks_m_.end(), lane[l].x0_m) -
                                              kinks_m_.begin());
    for (auto* v : {&ws.q_start, &ws.qd_start, &ws.qdd_start}) v->assign(n * lanes_n, 0.0);
    ws.kink_columns.assign(2 * width + 3 * n, 0.0);
  }
  const auto at_kink = [&](std::size_t l, double s, double theta) {
    double* const below = ws.kink_columns.data();
    double* const above = below + width;
    double* const kq = above + width;
    double* const kqd = kq + n;
    double* const kqdd = kqd + n;
    std::fill(below, below + 2 * width, 0.0);
    table_columns_at(s, true, below);
    table_columns_at(s, false, above);
    // Quintic Hermite weights of the values and derivatives at the step's
    // start (0) and end (1), and of its derivative.
    const double h = dt_s_, t2 = theta * theta, t3 = t2 * theta, t4 = t3 * theta, t5 = t4 * theta;
    const double w0 = 1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5, w3 = 1.0 - w0;
    const double w1 = (theta - 6.0 * t3 + 8.0 * t4 - 3.0 * t5) * h, w4 = (-4.0 * t3 + 7.0 * t4 - 3.0 * t5) * h;
    const double w2 = 0.5 * (t2 - 3.0 * t3 + 3.0 * t4 - t5) * h * h, w5 = 0.5 * (t3 - 2.0 * t4 + t5) * h * h;
    const double d0 = (-30.0 * t2 + 60.0 * t3 - 30.0 * t4) / h, d3 = -d0;
    const double d1 = 1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4, d4 = -12.0 * t2 + 28.0 * t3 - 15.0 * t4;
    const double d2 = (theta - 4.5 * t2 + 6.0 * t3 - 2.5 * t4) * h, d5 = (1.5 * t2 - 4.0 * t3 + 2.5 * t4) * h;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = k * lanes_n + l;
      const double q0 = ws.q_start[i], qd0 = ws.qd_start[i], qdd0 = ws.qdd_start[i];
      const double q1 = lane_of(q[k], l), qd1 = lane_of(qd[k], l), qdd1 = lane_of(qdd[k], l);
      kq[k] = w0 * q0 + w1 * qd0 + w2 * qdd0 + w3 * q1 + w4 * qd1 + w5 * qdd1;
      kqd[k] = d0 * q0 + d1 * qd0 + d2 * qdd0 + d3 * q1 + d4 * qd1 + d5 * qdd1;
      const ModalStep& m = steps_[k];
      kqdd[k] = below[k] - 2.0 * m.zeta * m.omega * kqd[k] - m.omega * m.omega * kq[k];
    }
    for (const double* side : {below, above}) {
      for (std::size_t f = 0; f < n_forms; ++f) ws.form_values[f] = side[n + f];
      sections_->add_dynamic_part(kq, kqd, kqdd, below, ws.form_values.data());
      if (!fold_forms) {
        out[l].sections->update(ws.form_values);
        continue;
      }
      for (std::size_t f = 0; f < n_forms; ++f) {
        const double v = ws.form_values[f];
        lane_of(max_abs_form[f], l) = std::max(lane_of(max_abs_form[f], l), std::abs(v));
        lane_of(max_form[f], l) = std::max(lane_of(max_form[f], l), v);
      }
    }
  };

  // The forms' peaks between samples, refined chunk by chunk: each segment
  // of a lane's samples between two kinks, over the middle samples whose
  // neighbours are both recorded (up to sample `upto`), with the largest
  // |value| so far. A vertex refine_max_abs skips against it is below it,
  // so below the run's; the maximum of the run's largest |value| and of
  // these is the bits of refining the whole run against the run's largest.
  std::vector<double> form_refined(n_forms * lanes_n, 0.0);
  std::array<long, L> next_middle{};
  std::array<std::size_t, L> split_at{};
  next_middle.fill(1);
  const bool refine_forms = fold_forms && kinks;
  std::vector<char> scan(n_forms, 1);
  const auto refine_window = [&](long upto) {
    for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) {
      const long last_middle = std::min(upto, last_step[l]) - 1;
      const std::vector<long>& splits = ws.kink_splits[l];
      std::size_t& k = split_at[l];
      long i = next_middle[l];
      // Which forms' windows may hold a vertex above the largest |value|.
      bool any = false;
      for (std::size_t f = 0; f < n_forms; ++f) {
        scan[f] = form_bounds.may_beat(f, l, lane_of(max_abs_form[f], l));
        any = any || scan[f];
      }
      // The cursor moves on whether or not a window is scanned.
      while (true) {
        // Past the pairs that end at or before i. The last pair's second
        // sample may still move on (a kink in the next step): it is kept.
        while (k + 1 < splits.size() && i >= splits[k]) {
          i = std::max(i, splits[k + 1] + 1);
          if (k + 2 >= splits.size()) break;
          k += 2;
        }
        if (i > last_middle) break;
        const long segment_end = k + 1 < splits.size() && i < splits[k] ? splits[k] : last_middle + 1;
        const long to = std::min(last_middle, segment_end - 1);
        for (std::size_t f = 0; any && f < n_forms; ++f) {
          if (!scan[f]) continue;
          const double* h = window_of[f * lanes_n + l] + (i - 1 - window_base);
          double& best = form_refined[f * lanes_n + l];
          best = std::max(best, refine_max_abs(h, static_cast<std::size_t>(to - i + 3), 1,
                                               lane_of(max_abs_form[f], l), code));
        }
        i = to + 1;
      }
      next_middle[l] = i;
    }
  };
  std::vector<double> deck_refined(2 * np * lanes_n, 0.0);
  std::array<long, L> deck_next_middle{};
  deck_next_middle.fill(1);
  const auto refine_deck = [&](long upto) {
    for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) {
      const long i = deck_next_middle[l], last_middle = std::min(upto, last_step[l]) - 1;
      if (i > last_middle) continue;
      for (std::size_t j = 0; j < 2 * np; ++j) {
        const double largest = lane_of(j % 2 == 0 ? max_u[j / 2] : max_a[j / 2], l);
        if (!deck_bounds.may_beat(j, l, largest)) continue;
        const double* kept = (j % 2 == 0 ? ws.displacement : ws.acceleration)[l][j / 2].data() + (i - 1);
        double& best = deck_refined[j * lanes_n + l];
        best = std::max(best, refine_max_abs(kept, static_cast<std::size_t>(last_middle - i + 3), 1, largest, code));
      }
      deck_next_middle[l] = last_middle + 1;
    }
    deck_bounds.next_chunk();
  };

  // Start from the static modal response under the loads at t = 0, as the
  // FE rung starts from the static equilibrium.
  for (std::size_t l = 0; l < lanes_n; ++l)
    modal_load(lane[l].x0_m, ws.p.data() + l, lanes_n, ws.piece.data() + l, ws);
  for (std::size_t k = 0; k < n; ++k) q[k] = p[k] * inverse_omega2_[k];
  record(0, 0.0, histories != nullptr);
  const std::size_t n_rails = rails_.size();
  // The loads of a chunk of steps are evaluated first into ws.chunk (a row
  // per step: the padded columns of every lane, lane-minor): those cubics
  // do not wait for each other, while the recurrence that follows is one
  // chain per lane. Each value is the same expression as when it is
  // evaluated in its step.
  const std::size_t row = padded_width * lanes_n;
  ws.chunk.assign(static_cast<std::size_t>(kChunkSteps) * row, 0.0);
  for (long first = 0; first < steps; first += kChunkSteps) {
    const long end = std::min(steps, first + kChunkSteps);
    for (long step = first; step < end; ++step) {
      double* const loads = ws.chunk.data() + static_cast<std::size_t>(step - first) * row;
      // Each lane's position on its rails' tables. A lane that has ended (or
      // idles) gets zero loads: finite, unread. A position on a breakpoint
      // or off the table takes modal_load.
      bool all_inside = lanes_n == kColumnGroup;
      std::array<bool, L> inside{};
      for (std::size_t l = 0; l < lanes_n; ++l) {
        double* pn = loads + l;
        if (step >= std::max(first, last_step[l])) {
          for (std::size_t k = 0; k < padded_width; ++k) pn[k * lanes_n] = 0.0;
          all_inside = false;
          continue;
        }
        const double x = lane[l].x0_m + lane[l].speed_mps * (static_cast<double>(step + 1) * dt_s_);
        bool inline_ok = true;
        for (std::size_t r = 0; r < n_rails && inline_ok; ++r) {
          const std::vector<double>& b = rails_[r].breaks;
          std::size_t& i = ws.piece[r * lanes_n + l];
          if (b.size() < 2 || x < b.front() || x >= b.back()) inline_ok = false;
          else {
            while (x >= b[i + 1]) ++i;  // x < b.back(): stops at the last piece
            inline_ok = x != b[i];
            ws.offset[r * lanes_n + l] = x - b[i];
          }
        }
        if (!inline_ok) {
          modal_load(x, pn, lanes_n, ws.piece.data() + l, ws);
          all_inside = false;
          continue;
        }
        inside[l] = true;
      }
      // One cubic per column from the train's table, by Horner's rule on a
      // group of columns at once: in each the scalar expression of
      // modal_load, so the same bits. The first rail's loads are the sum's
      // first terms (0 + v == v, bit for bit).
      if constexpr (L == 4) {
        if (all_inside) {
          // Every lane inside: the four lanes' values of a group, transposed
          // into the lane-minor row (moves only: the same bits), one
          // vector store per column.
          using Mask = long long __attribute__((vector_size(4 * sizeof(long long))));
          for (std::size_t r = 0; r < n_rails; ++r) {
            const double* d[4];
            Columns u[4];
            for (std::size_t l = 0; l < 4; ++l) {
              d[l] = rails_[r].pieces.data() + piece_index(ws.piece[r * 4 + l], 0, 0);
              u[l] = Columns{} + ws.offset[r * 4 + l];
            }
            for (std::size_t k0 = 0; k0 < width; k0 += kColumnGroup) {
              Columns v[4];
              for (std::size_t l = 0; l < 4; ++l) {
                const Columns c0 = *reinterpret_cast<const Columns*>(d[l]);
                const Columns c1 = *reinterpret_cast<const Columns*>(d[l] + kColumnGroup);
                const Columns c2 = *reinterpret_cast<const Columns*>(d[l] + 2 * kColumnGroup);
                const Columns c3 = *reinterpret_cast<const Columns*>(d[l] + 3 * kColumnGroup);
                v[l] = ((c3 * u[l] + c2) * u[l] + c1) * u[l] + c0;
                d[l] += 4 * kColumnGroup;
              }
              const Columns t0 = __builtin_shuffle(v[0], v[1], Mask{0, 4, 2, 6});
              const Columns t1 = __builtin_shuffle(v[0], v[1], Mask{1, 5, 3, 7});
              const Columns t2 = __builtin_shuffle(v[2], v[3], Mask{0, 4, 2, 6});
              const Columns t3 = __builtin_shuffle(v[2], v[3], Mask{1, 5, 3, 7});
              const Columns by_column[4] = {__builtin_shuffle(t0, t2, Mask{0, 1, 4, 5}),
                                            __builtin_shuffle(t1, t3, Mask{0, 1, 4, 5}),
                                            __builtin_shuffle(t0, t2, Mask{2, 3, 6, 7}),
                                            __builtin_shuffle(t1, t3, Mask{2, 3, 6, 7})};
              for (std::size_t j = 0; j < kColumnGroup; ++j) {
                V& to = *reinterpret_cast<V*>(loads + (k0 + j) * 4);
                to = r == 0 ? by_column[j] : to + by_column[j];
              }
            }
          }
          continue;
        }
      }
      // Lane by lane (one lane alone, or a group with a lane off the
      // table): column by column, the columns alone (no padding).
      for (std::size_t l = 0; l < lanes_n; ++l) {
        if (!inside[l]) continue;
        for (std::size_t r = 0; r < n_rails; ++r)
          piece_load(rails_[r], ws.piece[r * lanes_n + l], ws.offset[r * lanes_n + l], loads + l, lanes_n, r == 0);
      }
    }
    for (long step = first; step < end; ++step) {
      const double t_new = static_cast<double>(step + 1) * dt_s_;
      V* const p_next = reinterpret_cast<V*>(ws.chunk.data() + static_cast<std::size_t>(step - first) * row);
      // Does an axle of a running lane cross a kink in this step?
      bool crossing = false;
      for (std::size_t l = 0; kinks && l < static_cast<std::size_t>(count); ++l)
        crossing = crossing || (step < last_step[l] && next_kink[l] < kinks_m_.size() &&
                                kinks_m_[next_kink[l]] <= lane_x(l, step + 1));
      if (crossing) {
        std::copy(ws.q.begin(), ws.q.end(), ws.q_start.begin());
        std::copy(ws.qd.begin(), ws.qd.end(), ws.qd_start.begin());
        std::copy(ws.qdd.begin(), ws.qdd.end(), ws.qdd_start.begin());
      }
      bool finite = true;
      V zero{};
      for (std::size_t k = 0; k < n; ++k) {
        // ModalStep::advance, lane by lane.
        const ModalStep& m = steps_[k];
        const V change = p_next[k] - p[k];
        const V load_q = m.g0[0] * p[k] + m.g1_per_dt[0] * change;
        const V load_qd = m.g0[1] * p[k] + m.g1_per_dt[1] * change;
        const V q1 = (m.phi[0][0] * q[k] + m.phi[0][1] * qd[k]) + load_q;
        const V qd1 = (m.phi[1][0] * q[k] + m.phi[1][1] * qd[k]) + load_qd;
        q[k] = q1;
        qd[k] = qd1;
        qdd[k] = p_next[k] - 2.0 * m.zeta * m.omega * qd1 - m.omega * m.omega * q1;
        zero += q1 * 0.0;  // stays 0 while finite, NaN otherwise
      }
      for (std::size_t l = 0; l < lanes_n; ++l) finite = finite && lane_of(zero, l) == 0.0;
      p = p_next;
      // A lane whose coordinates are no longer finite ends here (the lanes
      // that run on record their steps, last_step[l], at the end).
      for (std::size_t l = 0; l < lanes_n && !finite; ++l) {
        if (step >= last_step[l]) continue;
        bool lane_finite = true;
        for (std::size_t k = 0; k < n; ++k) lane_finite = lane_finite && std::isfinite(lane_of(q[k], l));
        if (lane_finite) continue;
        if (l < static_cast<std::size_t>(count))
          out[l].status = {StatusCode::kDiverged, fmt::format("step {}: non-finite modal coordinates", step + 1)};
        last_step[l] = step;  // records nothing more
        all_until = std::min(all_until, step);
      }
      const bool store = histories != nullptr && last_step[0] > step &&
                         ((step + 1) % stride == 0 || step + 1 == lanes[0].n_steps);
      record(step + 1, t_new, store);
      for (std::size_t l = 0; crossing && l < static_cast<std::size_t>(count); ++l) {
        if (step >= last_step[l]) continue;  // ended before this step's end
        const double x_start = lane_x(l, step), x_end = lane_x(l, step + 1);
        while (next_kink[l] < kinks_m_.size() && kinks_m_[next_kink[l]] <= x_end) {
          const double at = kinks_m_[next_kink[l]++];
          at_kink(l, at, x_end > x_start ? std::clamp((at - x_start) / (x_end - x_start), 0.0, 1.0) : 1.0);
          // The samples before the kink end at this step's start; those
          // after it begin at its end, or one later when the kink is on that
          // sample (its value there is one side's).
          std::vector<long>& splits = ws.kink_splits[l];
          const long after = at == x_end ? step + 2 : step + 1;
          if (!splits.empty() && splits.back() > step) splits.back() = std::max(splits.back(), after);
          else {
            splits.push_back(step);
            splits.push_back(after);
          }
        }
      }
    }
    refine_deck(end);
    if (fold_forms) {
      if (refine_forms) refine_window(end);
      form_bounds.next_chunk();
      // The next chunk's window starts with this one's last two samples.
      for (double* w : window_of) std::copy(w + (end - 1 - window_base), w + (end + 1 - window_base), w);
      window_base = end - 1;
    }
    // The chunk is refilled next: the last loads move out of it.
    std::copy(reinterpret_cast<const double*>(p), reinterpret_cast<const double*>(p) + row, ws.p.data());
    p = reinterpret_cast<V*>(ws.p.data());
  }
  for (int l = 0; l < count; ++l) {
    ModalSweepRun& o = out[l];
    o.steps = last_step[static_cast<std::size_t>(l)];
    // The peaks from the kept samples, each refined between its samples.
    if (fold_forms) {
      // A form's samples between two kinks are smooth: each such segment is
      // refined as the deck's peaks (a parabola across a kink would follow
      // neither side). A form read signed (a reaction) is refined only
      // where its largest value is also its largest |value|.
      // (Refined chunk by chunk above.)
      for (std::size_t f = 0; f < n_forms; ++f) {
        const auto lane = static_cast<std::size_t>(l);
        const double m = lane_of(form_signed_[f] ? max_form[f] : max_abs_form[f], lane);
        if (!kinks || (form_signed_[f] && m < lane_of(max_abs_form[f], lane))) {
          ws.form_values[f] = m;
          continue;
        }
        ws.form_values[f] = std::max(m, form_refined[f * lanes_n + lane]);
      }
      o.sections->update(ws.form_values);
    }
    o.max_abs_displacement_m.resize(np);
    o.max_abs_acceleration_mps2.resize(np);
    const auto lane = static_cast<std::size_t>(l);
    // (Refined chunk by chunk above.)
    for (std::size_t i = 0; i < np; ++i) {
      o.max_abs_displacement_m[i] = std::max(lane_of(max_u[i], lane), deck_refined[2 * i * lanes_n + lane]);
      o.max_abs_acceleration_mps2[i] = std::max(lane_of(max_a[i], lane), deck_refined[(2 * i + 1) * lanes_n + lane]);
    }
  }
}

void ModalSweep::run_four_lanes(const SweepLane* lanes, int count, ModalSweepRun* out, ModalSweepWorkspace& ws) const {
  run_lanes<kSweepLanes>(lanes, count, out, ws, nullptr, 1, LaneCode::kPortable);
}

// The same code for a processor with AVX2: a vector of four doubles is one
// register and one instruction. No FMA: each product is rounded before its
// sum, as in the baseline code, so the bits are the same.
__attribute__((target("avx2"))) void ModalSweep::run_four_lanes_avx2(const SweepLane* lanes, int count,
                                                                      ModalSweepRun* out,
                                                                      ModalSweepWorkspace& ws) const {
  run_lanes<kSweepLanes>(lanes, count, out, ws, nullptr, 1, LaneCode::kFastest);
}

ModalSweepRun ModalSweep::run(double x0_m, double speed_mps, long n_steps, ModalSweepWorkspace& ws,
                              Histories* histories, int history_stride) const {
  const SweepLane lane{x0_m, speed_mps, n_steps};
  ModalSweepRun out;
  run_lanes<1>(&lane, 1, &out, ws, histories, history_stride, LaneCode::kFastest);
  check_plausible(out);
  return out;
}

std::vector<ModalSweepRun> ModalSweep::run_group(const std::vector<SweepLane>& lanes, ModalSweepWorkspace& ws,
                                                 LaneCode code) const {
  if (lanes.size() > static_cast<std::size_t>(kSweepLanes))
    throw std::invalid_argument("ModalSweep::run_group: more runs than lanes");
  std::vector<ModalSweepRun> out(lanes.size());
  const int count = static_cast<int>(lanes.size());
  if (count == 1) run_lanes<1>(lanes.data(), 1, out.data(), ws, nullptr, 1, code);
  else if (count > 1 && use_avx2(code)) run_four_lanes_avx2(lanes.data(), count, out.data(), ws);
  else if (count > 1) run_four_lanes(lanes.data(), count, out.data(), ws);
  for (ModalSweepRun& r : out) check_plausible(r);
  return out;
}

void ModalSweep::check_plausible(ModalSweepRun& run) const {
  if (!run.status.ok()) return;
  const std::vector<OutputPoint>& points = basis_.structure().outputs();
  for (std::size_t i = 0; i < run.max_abs_displacement_m.size() && i < points.size(); ++i)
    if (run.max_abs_displacement_m[i] > u_limit_m_) {
      run.status = {StatusCode::kUnstable,
                    fmt::format("deck displacement {:.4g} m at output point '{}' exceeds {:.4g} m (max(0.1 m, "
                                "span/100)), implausible for this structure: check its stiffness and mass and their "
                                "units",
                                run.max_abs_displacement_m[i], points[i].name, u_limit_m_)};
      return;
    }
}

}  // namespace railvsi
