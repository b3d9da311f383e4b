#include "generators/deck_3d.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/beam_element.hpp"
#include "generators/bridge_2d.hpp"
#include "generators/hex8_element.hpp"
#include "model/rayleigh.hpp"

namespace railvsi {
namespace {

constexpr double kJointTol_m = 1e-9;

double deck_width_m(const Deck3dOptions& o) { return o.box ? o.box->top_width_m : o.width_m; }
double deck_depth_m(const Deck3dOptions& o) { return o.box ? o.box->depth_m : o.depth_m; }

// Half the box from the centreline out: the void, a web, the overhang of
// the top slab (none when the slabs are equally wide).
std::vector<double> box_half_widths_m(const BoxGirderSection& b) {
  std::vector<double> w{0.5 * b.bottom_width_m - b.web_thickness_m, b.web_thickness_m};
  if (b.top_width_m > b.bottom_width_m) w.push_back(0.5 * (b.top_width_m - b.bottom_width_m));
  return w;
}
std::vector<double> box_heights_m(const BoxGirderSection& b) {
  return {b.bottom_thickness_m, b.depth_m - b.top_thickness_m - b.bottom_thickness_m, b.top_thickness_m};
}
int min_ny(const Deck3dOptions& o) { return o.box ? 2 * static_cast<int>(box_half_widths_m(*o.box).size()) : 2; }
int min_nz(const Deck3dOptions& o) { return o.box ? 3 : 1; }
// A box's end diaphragms take one element at each end of a span.
int min_nx(const Deck3dOptions& o) { return o.box ? 4 : 1; }

void check_options(const Deck3dOptions& o) {
  if (o.spans_m.empty()) throw InputError("/spans_m", "at least one span is needed");
  for (std::size_t i = 0; i < o.spans_m.size(); ++i)
    if (!(o.spans_m[i] > 0.0)) throw InputError(fmt::format("/spans_m/{}", i), "span length must be > 0");
  const std::pair<const char*, double> positive[] = {
      {"width_m", o.width_m},           {"depth_m", o.depth_m},
      {"E_Pa", o.E_Pa},                 {"density_kg_per_m3", o.density_kg_per_m3},
      {"rail_EI_Nm2", o.rail_EI_Nm2},   {"rail_mass_kg_per_m", o.rail_mass_kg_per_m},
      {"pad_k_N_per_m", o.pad_k_N_per_m}, {"sleeper_spacing_m", o.sleeper_spacing_m}};
  for (const auto& [key, value] : positive)
    if (!(value > 0.0)) throw InputError(fmt::format("/{}", key), "must be > 0");
  const std::pair<const char*, double> non_negative[] = {
      {"pad_c_Ns_per_m", o.pad_c_Ns_per_m}, {"approach_m", o.approach_m}, {"exit_m", o.exit_m}};
  for (const auto& [key, value] : non_negative)
    if (!(value >= 0.0)) throw InputError(fmt::format("/{}", key), "must be >= 0");
  if (!(o.poisson > -1.0 && o.poisson < 0.5)) throw InputError("/poisson", "must be in (-1, 0.5)");
  if (!(o.damping_ratio >= 0.0 && o.damping_ratio < 1.0)) throw InputError("/damping_ratio", "must be in [0, 1)");
  if (o.box) {
    try {
      check_box_girder(*o.box);
    } catch (const InputError& e) {
      throw InputError("/box" + e.json_path(), e.what());
    }
  }
  if (o.rail_y_m.empty()) throw InputError("/rail_y_m", "at least one rail is needed");
  for (std::size_t r = 0; r < o.rail_y_m.size(); ++r)
    if (!(std::abs(o.rail_y_m[r]) <= 0.5 * deck_width_m(o)))
      throw InputError(fmt::format("/rail_y_m/{}", r),
                       fmt::format("rail at y = {} m is off the deck (width {} m)", o.rail_y_m[r], deck_width_m(o)));
  if (o.mesh) {
    if (o.mesh->nx.size() != o.spans_m.size())
      throw InputError("/mesh/nx", fmt::format("has {} entries for {} spans", o.mesh->nx.size(), o.spans_m.size()));
    for (std::size_t s = 0; s < o.mesh->nx.size(); ++s)
      if (o.mesh->nx[s] < min_nx(o))
        throw InputError(fmt::format("/mesh/nx/{}", s),
                         o.box ? "must be >= 4 for a box girder (its end diaphragms take one element at each end)"
                               : "must be >= 1");
    if (o.mesh->ny < 1) throw InputError("/mesh/ny", "must be >= 1");
    if (o.mesh->nz < 1) throw InputError("/mesh/nz", "must be >= 1");
    if (o.box && (o.mesh->ny < min_ny(o) || o.mesh->ny % 2 != 0))
      throw InputError("/mesh/ny", fmt::format("a box girder needs an even ny >= {} (a line on the centreline, "
                                               "each plate at least one element)",
                                               min_ny(o)));
    if (o.box && o.mesh->nz < min_nz(o))
      throw InputError("/mesh/nz", "a box girder needs nz >= 3 (each plate at least one element)");
  }
}

// n cells over regions of these lengths: one each, then one at a time to
// the region with the largest cells, so that the cells are as even as the
// thinnest plate allows and every face is a grid line.
std::vector<int> split_cells(const std::vector<double>& lengths, int n) {
  std::vector<int> count(lengths.size(), 1);
  for (int placed = static_cast<int>(lengths.size()); placed < n; ++placed) {
    std::size_t widest = 0;
    for (std::size_t r = 1; r < lengths.size(); ++r)
      if (lengths[r] / count[r] > lengths[widest] / count[widest]) widest = r;
    ++count[widest];
  }
  return count;
}

// Grid lines from `start` over the regions, split as counted.
std::vector<double> region_lines(double start, const std::vector<double>& lengths, const std::vector<int>& count) {
  std::vector<double> lines{start};
  double at = start;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    for (int q = 1; q < count[r]; ++q) lines.push_back(at + lengths[r] * q / count[r]);
    at += lengths[r];
    lines.push_back(at);
  }
  return lines;
}

// The ny x nz grid of the cross-section: its lines, its cells that are
// concrete, and the nodes of those cells (the others carry no DOFs). A box
// has a solid diaphragm in the end element of each span: there (`end`),
// its void is concrete too. Without diaphragms the end sections distort
// freely and the first twisting mode is a racking of the cell at about a
// third of the St Venant torsion frequency.
struct SectionGrid {
  int ny = 0, nz = 0;
  std::vector<double> y_m, z_m;    // ny + 1 and nz + 1 lines
  std::vector<double> dy_m, dz_m;  // cell sizes
  std::array<std::vector<char>, 2> concrete;  // [end] cell j + ny * k
  std::array<std::vector<char>, 2> used;      // [end] node j + (ny + 1) * k
  bool cell(int j, int k, bool end) const { return concrete[end][static_cast<std::size_t>(j + ny * k)] != 0; }
  bool node(int j, int k, bool end) const { return used[end][static_cast<std::size_t>(j + (ny + 1) * k)] != 0; }
  long nodes(bool end) const { return std::count(used[end].begin(), used[end].end(), 1); }
  long soffit_nodes() const { return std::count(used[0].begin(), used[0].begin() + ny + 1, 1); }
};

// The diaphragm elements of a span of nx elements: the two end ones and,
// for a box with intermediate diaphragms, the element holding each x =
// L m / (n + 1). Only a box's diaphragms differ from the rest of the deck.
std::vector<char> diaphragm_elements(const Deck3dOptions& o, int nx) {
  std::vector<char> d(static_cast<std::size_t>(nx), 0);
  d.front() = d.back() = 1;
  const int n = o.box ? o.box->intermediate_diaphragms : 0;
  for (int m = 1; m <= n; ++m) {
    const int e = std::clamp(static_cast<int>(std::floor(static_cast<double>(nx) * m / (n + 1))), 0, nx - 1);
    d[static_cast<std::size_t>(e)] = 1;
  }
  return d;
}
// Station i (an element end) is a node of a diaphragm element.
bool is_diaphragm_station(const std::vector<char>& elements, int i) {
  const auto nx = static_cast<int>(elements.size());
  return (i > 0 && elements[static_cast<std::size_t>(i - 1)]) || (i < nx && elements[static_cast<std::size_t>(i)]);
}
long diaphragm_stations(const std::vector<char>& elements) {
  long n = 0;
  for (int i = 0; i <= static_cast<int>(elements.size()); ++i) n += is_diaphragm_station(elements, i);
  return n;
}

SectionGrid section_grid(const Deck3dOptions& o, int ny, int nz) {
  SectionGrid s;
  s.ny = ny;
  s.nz = nz;
  if (!o.box) {  // the solid rectangle, uniform
    for (int j = 0; j <= ny; ++j) s.y_m.push_back(-0.5 * o.width_m + o.width_m * j / ny);
    for (int k = 0; k <= nz; ++k) s.z_m.push_back(o.depth_m * k / nz);
    s.dy_m.assign(static_cast<std::size_t>(ny), o.width_m / ny);
    s.dz_m.assign(static_cast<std::size_t>(nz), o.depth_m / nz);
    for (const bool end : {false, true}) {
      s.concrete[end].assign(static_cast<std::size_t>(ny * nz), 1);
      s.used[end].assign(static_cast<std::size_t>((ny + 1) * (nz + 1)), 1);
    }
    return s;
  }
  const BoxGirderSection& b = *o.box;
  const std::vector<double> half = box_half_widths_m(b), heights = box_heights_m(b);
  const std::vector<double> out = region_lines(0.0, half, split_cells(half, ny / 2));
  for (std::size_t m = out.size(); m-- > 1;) s.y_m.push_back(-out[m]);
  s.y_m.insert(s.y_m.end(), out.begin(), out.end());
  s.z_m = region_lines(0.0, heights, split_cells(heights, nz));
  for (int j = 0; j < ny; ++j) s.dy_m.push_back(s.y_m[j + 1] - s.y_m[j]);
  for (int k = 0; k < nz; ++k) s.dz_m.push_back(s.z_m[k + 1] - s.z_m[k]);
  for (const bool end : {false, true}) {
    s.concrete[end].assign(static_cast<std::size_t>(ny * nz), 0);
    s.used[end].assign(static_cast<std::size_t>((ny + 1) * (nz + 1)), 0);
  }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const double y = std::abs(0.5 * (s.y_m[j] + s.y_m[j + 1])), z = 0.5 * (s.z_m[k] + s.z_m[k + 1]);
      const bool top = z > b.depth_m - b.top_thickness_m, under = y < 0.5 * b.bottom_width_m;
      const bool web = y > 0.5 * b.bottom_width_m - b.web_thickness_m;
      for (const bool end : {false, true}) {
        if (!(top || (under && (end || z < b.bottom_thickness_m || web)))) continue;
        s.concrete[end][static_cast<std::size_t>(j + ny * k)] = 1;
        for (int c = 0; c < 4; ++c)
          s.used[end][static_cast<std::size_t>(j + (c & 1) + (ny + 1) * (k + (c >> 1)))] = 1;
      }
    }
  return s;
}

double total_length_m(const Deck3dOptions& o) { return std::accumulate(o.spans_m.begin(), o.spans_m.end(), 0.0); }

// Rail nodes every sleeper spacing, from the start of the approach (a whole
// number of spacings before x = 0) past the end of the exit.
std::vector<double> rail_node_x(const Deck3dOptions& o) {
  const double s = o.sleeper_spacing_m;
  const int before = static_cast<int>(std::ceil(o.approach_m / s - 1e-9));
  const double x_start = -before * s;
  const int nodes = static_cast<int>(std::ceil((total_length_m(o) + o.exit_m - x_start) / s - 1e-9)) + 1;
  std::vector<double> x(static_cast<std::size_t>(std::max(nodes, 2)));
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = x_start + static_cast<double>(k) * s;
  return x;
}

// Each rail: (v, rotation) per node, v fixed at both anchored ends.
long rail_dofs(const Deck3dOptions& o) {
  return static_cast<long>(o.rail_y_m.size()) * (2 * static_cast<long>(rail_node_x(o).size()) - 2);
}

// Vertical support along the bottom edge of both end faces; a fixed bearing
// (u, v) at the bottom centre of the first end face and a guided one (v) at
// the bottom centre of the last: three constraints for the three rigid-body
// motions the vertical supports leave (x, y and rotation about z).
long fixed_dofs_per_span(const SectionGrid& s) { return 2L * s.soffit_nodes() + 3; }

// One span's structured grid of nodes.
struct SpanGrid {
  double x0_m = 0.0, length_m = 0.0;
  int nx = 0, ny = 0, nz = 0;
  int first_node = 0;
  std::vector<char> diaphragm;  // per element (diaphragm_elements)
  bool diaphragm_element(int i) const { return diaphragm[static_cast<std::size_t>(i)] != 0; }
  bool diaphragm_station(int i) const { return is_diaphragm_station(diaphragm, i); }
  int node(int i, int j, int k) const { return first_node + i + (nx + 1) * (j + (ny + 1) * k); }
  int num_nodes() const { return (nx + 1) * (ny + 1) * (nz + 1); }
  // Only for nodes of the section (a box's void has none).
  bool fixed(int i, int j, int k, int c) const {
    if (k != 0) return false;
    const bool end = (i == 0 || i == nx), centre = (j == ny / 2);
    if (c == 2) return end;
    if (c == 1) return end && centre;
    return i == 0 && centre;
  }
};

// Spring (or dashpot) of value k on the relative displacement sum g_i u_i;
// entries with DOF -1 (fixed) drop out. k * (ga * gb): bit-for-bit
// symmetric, as the lower triangle written to a file is mirrored on reading.
void add_link(std::vector<Triplet>& into, const std::vector<std::pair<int, double>>& g, double k) {
  for (const auto& [a, ga] : g)
    for (const auto& [b, gb] : g)
      if (a >= 0 && b >= 0) into.emplace_back(a, b, k * (ga * gb));
}

SparseMatrix to_sparse(int n, const std::vector<Triplet>& t) {
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// The deck stiffness in compressed columns, straight from the structured
// grid: the element blocks of each node pair are summed into a 27-point
// stencil per node (every pair of nodes within one grid step shares an
// element), then written column by column. Triplets would need ~600 bytes
// per node more, at 230,000 DOFs a gigabyte.
struct CompressedColumns {
  std::vector<int> outer{0}, inner;
  std::vector<double> values;
};

// cell_K[end][j + ny * k]: the stiffness of the elements of that cell of
// the section (in an end element or not), null where there is no
// concrete. Node pairs that share no element get no entry.
void append_span_columns(const SpanGrid& g, const std::array<std::vector<const Matrix24*>, 2>& cell_K,
                         const std::vector<std::array<int, 3>>& node_dofs, CompressedColumns& out) {
  const int nn = g.num_nodes();
  std::vector<double> blocks(static_cast<std::size_t>(nn) * 27 * 9, 0.0);
  std::vector<char> coupled(static_cast<std::size_t>(nn) * 27, 0);
  const auto slot = [](int di, int dj, int dk) { return (dk + 1) * 9 + (dj + 1) * 3 + (di + 1); };
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const Matrix24* Ke_cell = cell_K[g.diaphragm_element(i)][static_cast<std::size_t>(j + g.ny * k)];
        if (Ke_cell == nullptr) continue;
        const Matrix24& Ke = *Ke_cell;
        for (int a = 0; a < 8; ++a) {
          const int ai = a & 1, aj = (a >> 1) & 1, ak = (a >> 2) & 1;
          const int na = g.node(i + ai, j + aj, k + ak) - g.first_node;
          for (int b = 0; b < 8; ++b) {
            const int s = slot((b & 1) - ai, ((b >> 1) & 1) - aj, ((b >> 2) & 1) - ak);
            coupled[static_cast<std::size_t>(na) * 27 + s] = 1;
            double* block = &blocks[(static_cast<std::size_t>(na) * 27 + s) * 9];
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) block[r * 3 + c] += Ke(3 * a + r, 3 * b + c);
          }
        }
    }
  out.inner.reserve(out.inner.size() + static_cast<std::size_t>(nn) * 81);
  out.values.reserve(out.values.size() + static_cast<std::size_t>(nn) * 81);
  for (int k = 0; k <= g.nz; ++k)
    for (int j = 0; j <= g.ny; ++j)
      for (int i = 0; i <= g.nx; ++i) {
        const int p = g.node(i, j, k);
        for (int c = 0; c < 3; ++c) {
          if (node_dofs[static_cast<std::size_t>(p)][static_cast<std::size_t>(c)] < 0) continue;
          // Rows in increasing DOF order: neighbours by increasing node index, then component.
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                if (i + di < 0 || i + di > g.nx || j + dj < 0 || j + dj > g.ny || k + dk < 0 || k + dk > g.nz)
                  continue;
                const int q = g.node(i + di, j + dj, k + dk);
                const std::size_t pq = static_cast<std::size_t>(p - g.first_node) * 27 + slot(di, dj, dk);
                if (!coupled[pq]) continue;
                // K(q r, p c) = K(p c, q r): block (p, q), row c, column r.
                const double* block = &blocks[pq * 9];
                for (int r = 0; r < 3; ++r) {
                  const int row = node_dofs[static_cast<std::size_t>(q)][static_cast<std::size_t>(r)];
                  if (row < 0) continue;
                  out.inner.push_back(row);
                  out.values.push_back(block[c * 3 + r]);
                }
              }
          out.outer.push_back(static_cast<int>(out.inner.size()));
        }
      }
}

double mesh_aspect(const Deck3dOptions& o, const Deck3dMesh& m) {
  double dx_min = 1e300, dx_max = 0.0;
  for (std::size_t s = 0; s < o.spans_m.size(); ++s) {
    dx_min = std::min(dx_min, o.spans_m[s] / m.nx[s]);
    dx_max = std::max(dx_max, o.spans_m[s] / m.nx[s]);
  }
  const SectionGrid s = section_grid(o, m.ny, m.nz);
  const auto [dy_min, dy_max] = std::minmax_element(s.dy_m.begin(), s.dy_m.end());
  const auto [dz_min, dz_max] = std::minmax_element(s.dz_m.begin(), s.dz_m.end());
  return std::max({dx_max, *dy_max, *dz_max}) / std::min({dx_min, *dy_min, *dz_min});
}

// Saint-Venant torsion constant of a solid rectangle (Timoshenko & Goodier,
// Theory of Elasticity, 3rd ed., 1970, section 109): with h the
// shorter side, J = b h^3 / 3 (1 - 192 h / (pi^5 b) sum over odd n of
// tanh(n pi b / 2h) / n^5).
double rectangle_torsion_constant_m4(double width_m, double depth_m) {
  const double b = std::max(width_m, depth_m), h = std::min(width_m, depth_m);
  double sum = 0.0;
  for (int n = 1; n < 100; n += 2) sum += std::tanh(n * std::numbers::pi * b / (2.0 * h)) / std::pow(n, 5);
  return b * std::pow(h, 3) / 3.0 * (1.0 - 192.0 * h / (std::pow(std::numbers::pi, 5) * b) * sum);
}

}  // namespace

void check_box_girder(const BoxGirderSection& b) {
  const std::pair<const char*, double> positive[] = {
      {"top_width_m", b.top_width_m},           {"top_thickness_m", b.top_thickness_m},
      {"bottom_width_m", b.bottom_width_m},     {"bottom_thickness_m", b.bottom_thickness_m},
      {"web_thickness_m", b.web_thickness_m},   {"depth_m", b.depth_m}};
  for (const auto& [key, value] : positive)
    if (!(value > 0.0 && std::isfinite(value))) throw InputError(fmt::format("/{}", key), "must be > 0");
  if (!(2.0 * b.web_thickness_m < b.bottom_width_m))
    throw InputError("/web_thickness_m", fmt::format("two webs of {} m leave no void in a bottom slab {} m wide "
                                                     "(a web must be thinner than half the bottom width)",
                                                     b.web_thickness_m, b.bottom_width_m));
  if (!(b.bottom_width_m <= b.top_width_m))
    throw InputError("/bottom_width_m", fmt::format("{} m is wider than the top slab ({} m); the webs are vertical "
                                                    "and stand on the edges of the bottom slab",
                                                    b.bottom_width_m, b.top_width_m));
  if (!(b.top_thickness_m + b.bottom_thickness_m < b.depth_m))
    throw InputError("/depth_m", fmt::format("{} m leaves no web between the slabs ({} m + {} m thick)", b.depth_m,
                                             b.top_thickness_m, b.bottom_thickness_m));
  if (b.intermediate_diaphragms < 0 || b.intermediate_diaphragms > 100)
    throw InputError("/intermediate_diaphragms", fmt::format("{} diaphragms per span: give 0 to 100", b.intermediate_diaphragms));
}

DeckSectionProperties deck_section_properties(const Deck3dOptions& o) {
  DeckSectionProperties p;
  if (!o.box) {
    p.area_m2 = o.width_m * o.depth_m;
    p.I_m4 = o.width_m * std::pow(o.depth_m, 3) / 12.0;
    p.I_lateral_m4 = o.depth_m * std::pow(o.width_m, 3) / 12.0;
    p.centroid_z_m = 0.5 * o.depth_m;
    p.torsion_J_m4 = rectangle_torsion_constant_m4(o.width_m, o.depth_m);
  } else {
    // Rectangles (width, height, centre z, centre |y|): slabs and webs.
    const BoxGirderSection& b = *o.box;
    const double web_h = b.depth_m - b.top_thickness_m - b.bottom_thickness_m;
    const double web_y = 0.5 * (b.bottom_width_m - b.web_thickness_m);
    const std::array<std::array<double, 4>, 4> parts{{
        {b.top_width_m, b.top_thickness_m, b.depth_m - 0.5 * b.top_thickness_m, 0.0},
        {b.bottom_width_m, b.bottom_thickness_m, 0.5 * b.bottom_thickness_m, 0.0},
        {b.web_thickness_m, web_h, b.bottom_thickness_m + 0.5 * web_h, web_y},
        {b.web_thickness_m, web_h, b.bottom_thickness_m + 0.5 * web_h, -web_y}}};
    double first_moment = 0.0;
    for (const auto& [w, h, z, y] : parts) {
      p.area_m2 += w * h;
      first_moment += w * h * z;
    }
    p.centroid_z_m = first_moment / p.area_m2;
    for (const auto& [w, h, z, y] : parts) {
      p.I_m4 += w * std::pow(h, 3) / 12.0 + w * h * std::pow(z - p.centroid_z_m, 2);
      p.I_lateral_m4 += h * std::pow(w, 3) / 12.0 + w * h * y * y;
    }
    // Bredt: the mid-lines of the slabs and webs enclose a rectangle.
    const double cell_w = b.bottom_width_m - b.web_thickness_m;
    const double cell_h = b.depth_m - 0.5 * (b.top_thickness_m + b.bottom_thickness_m);
    const double s_over_t = 2.0 * cell_h / b.web_thickness_m + cell_w / b.top_thickness_m + cell_w / b.bottom_thickness_m;
    p.torsion_J_m4 = 4.0 * std::pow(cell_w * cell_h, 2) / s_over_t;
  }
  p.polar_m4 = p.I_m4 + p.I_lateral_m4;
  return p;
}

long deck_3d_dofs(const Deck3dOptions& o, const Deck3dMesh& m) {
  long n = rail_dofs(o);
  const SectionGrid s = section_grid(o, m.ny, m.nz);
  for (const int nx : m.nx)
    n += 3L * ((nx + 1) * s.nodes(false) + diaphragm_stations(diaphragm_elements(o, nx)) * (s.nodes(true) - s.nodes(false))) -
         fixed_dofs_per_span(s);
  return n;
}

Deck3dMesh choose_deck_3d_mesh(const Deck3dOptions& o) {
  check_options(o);
  if (o.mesh) return *o.mesh;
  if (o.target_dofs <= 0) throw InputError("/target_dofs", "must be > 0");
  const double target = o.target_dofs, total = total_length_m(o);
  const auto spans = static_cast<long>(o.spans_m.size());
  // Every section (ny even, so that a node sits on the centreline; nz);
  // the elements along x follow from the target. Among meshes within 1 %
  // of the target, the one with the most cubic elements.
  Deck3dMesh best;
  double best_error = 1e300, best_aspect = 1e300;
  for (int nz = min_nz(o); nz <= 1000; ++nz) {
    bool reachable = false;
    for (int ny = min_ny(o); deck_width_m(o) / ny >= 0.25 * deck_depth_m(o) / nz; ny += 2) {
      Deck3dMesh m{std::vector<int>(o.spans_m.size(), 2), ny, nz};
      if (static_cast<double>(deck_3d_dofs(o, m)) > 1.05 * target) break;  // finer sections only grow
      reachable = true;
      const SectionGrid section = section_grid(o, ny, nz);
      const double per_station = 3.0 * static_cast<double>(section.nodes(false));
      const double stations = (target - rail_dofs(o) + spans * fixed_dofs_per_span(section)) / per_station;
      for (std::size_t s = 0; s < o.spans_m.size(); ++s)
        m.nx[s] = std::max(std::max(2, min_nx(o)), 2 * static_cast<int>(std::lround((stations - spans) * o.spans_m[s] / total / 2.0)));
      const double error = std::abs(static_cast<double>(deck_3d_dofs(o, m)) - target) / target;
      const double aspect = mesh_aspect(o, m);
      const bool better = (error <= 0.01 && (best_error > 0.01 || aspect < best_aspect)) ||
                          (error > 0.01 && best_error > 0.01 && error < best_error);
      if (better) {
        best = m;
        best_error = error;
        best_aspect = aspect;
      }
    }
    if (!reachable) break;
  }
  if (!(best_error <= 0.05))
    throw InputError("/target_dofs",
                     fmt::format("{} DOFs cannot be reached within 5 %: the nearest mesh has {} (the rails alone "
                                 "have {}; a shorter approach or exit track gives a smaller model)",
                                 o.target_dofs, best.nx.empty() ? rail_dofs(o) : deck_3d_dofs(o, best),
                                 rail_dofs(o)));
  return best;
}

Deck3d make_deck_3d(const Deck3dOptions& o) {
  Deck3d out;
  out.mesh = choose_deck_3d_mesh(o);
  const Deck3dMesh& mesh = out.mesh;
  const SectionGrid section = section_grid(o, mesh.ny, mesh.nz);
  const double total = total_length_m(o);
  const int n_total = static_cast<int>(deck_3d_dofs(o, mesh));

  // ---- deck nodes and DOFs, span by span
  std::vector<SpanGrid> grids;
  double x0 = 0.0;
  int first_node = 0, next_dof = 0;
  for (std::size_t s = 0; s < o.spans_m.size(); ++s) {
    SpanGrid g{x0, o.spans_m[s], mesh.nx[s], mesh.ny, mesh.nz, first_node, diaphragm_elements(o, mesh.nx[s])};
    for (int k = 0; k <= g.nz; ++k)
      for (int j = 0; j <= g.ny; ++j)
        for (int i = 0; i <= g.nx; ++i) {
          out.node_m.push_back({x0 + g.length_m * i / g.nx, section.y_m[static_cast<std::size_t>(j)],
                                section.z_m[static_cast<std::size_t>(k)]});
          std::array<int, 3> dofs{};
          for (int c = 0; c < 3; ++c)
            dofs[static_cast<std::size_t>(c)] =
                (!section.node(j, k, g.diaphragm_station(i)) || g.fixed(i, j, k, c)) ? -1 : next_dof++;
          out.node_dofs.push_back(dofs);
        }
    grids.push_back(g);
    first_node += g.num_nodes();
    x0 += o.spans_m[s];
  }
  const int deck_dofs = next_dof;

  // ---- deck stiffness and lumped mass
  CompressedColumns kd;
  kd.outer.reserve(static_cast<std::size_t>(n_total) + 1);
  std::vector<Triplet> m_deck;
  for (const SpanGrid& g : grids) {
    const double dx = g.length_m / g.nx;
    // One element stiffness per cell size (the solid section: one in all).
    std::vector<std::pair<std::array<double, 2>, Matrix24>> by_size;
    std::array<std::vector<const Matrix24*>, 2> cell_K;
    by_size.reserve(static_cast<std::size_t>(g.ny * g.nz));
    for (const bool end : {false, true}) {
      cell_K[end].assign(static_cast<std::size_t>(g.ny * g.nz), nullptr);
      for (int k = 0; k < g.nz; ++k)
        for (int j = 0; j < g.ny; ++j) {
          if (!section.cell(j, k, end)) continue;
          const std::array<double, 2> size{section.dy_m[static_cast<std::size_t>(j)],
                                           section.dz_m[static_cast<std::size_t>(k)]};
          auto it = std::find_if(by_size.begin(), by_size.end(), [&](const auto& e) { return e.first == size; });
          if (it == by_size.end())
            it = by_size.emplace(by_size.end(), size, hex8_box_stiffness(o.E_Pa, o.poisson, dx, size[0], size[1]));
          cell_K[end][static_cast<std::size_t>(j + g.ny * k)] = &it->second;
        }
    }
    append_span_columns(g, cell_K, out.node_dofs, kd);
    if (o.box) {
      // Each element's mass in equal eighths on its corners.
      std::vector<double> node_mass(static_cast<std::size_t>(g.num_nodes()), 0.0);
      for (int k = 0; k < g.nz; ++k)
        for (int j = 0; j < g.ny; ++j)
          for (int i = 0; i < g.nx; ++i)
            if (section.cell(j, k, g.diaphragm_element(i)))
              for (int a = 0; a < 8; ++a)
                node_mass[static_cast<std::size_t>(g.node(i + (a & 1), j + ((a >> 1) & 1), k + (a >> 2)) -
                                                   g.first_node)] +=
                    o.density_kg_per_m3 * dx * section.dy_m[static_cast<std::size_t>(j)] *
                    section.dz_m[static_cast<std::size_t>(k)] / 8.0;
      for (int p = 0; p < g.num_nodes(); ++p)
        for (const int d : out.node_dofs[static_cast<std::size_t>(g.first_node + p)])
          if (d >= 0) m_deck.emplace_back(d, d, node_mass[static_cast<std::size_t>(p)]);
      continue;
    }
    // Solid: every node's elements are equal, eighths of each on its corners.
    const double dy = o.width_m / g.ny, dz = o.depth_m / g.nz;
    const double eighth = o.density_kg_per_m3 * dx * dy * dz / 8.0;
    for (int k = 0; k <= g.nz; ++k)
      for (int j = 0; j <= g.ny; ++j)
        for (int i = 0; i <= g.nx; ++i) {
          const int elements = (i > 0 && i < g.nx ? 2 : 1) * (j > 0 && j < g.ny ? 2 : 1) * (k > 0 && k < g.nz ? 2 : 1);
          for (const int d : out.node_dofs[static_cast<std::size_t>(g.node(i, j, k))])
            if (d >= 0) m_deck.emplace_back(d, d, eighth * elements);
        }
  }
  kd.outer.resize(static_cast<std::size_t>(n_total) + 1, kd.outer.back());  // rail columns: empty
  const Eigen::Map<const SparseMatrix> K_deck(n_total, n_total, static_cast<Eigen::Index>(kd.values.size()),
                                              kd.outer.data(), kd.inner.data(), kd.values.data());
  const SparseMatrix M_deck = to_sparse(n_total, m_deck);

  // ---- rails on pads: on the deck's top face, or on rigid ground
  std::vector<Triplet> k_track, m_track, c_track;
  std::vector<RailLine> rails;
  const std::vector<double> rx = rail_node_x(o);
  const auto top_point = [&](const SpanGrid& g, double x, double y, double share) {
    const double fx = (x - g.x0_m) / (g.length_m / g.nx);
    const int i = std::clamp(static_cast<int>(std::floor(fx)), 0, g.nx - 1);
    int j = 0;
    double eta = 0.0;
    if (o.box) {  // lines at the plate faces, uneven
      const auto above = std::upper_bound(section.y_m.begin(), section.y_m.end(), y);
      j = std::clamp(static_cast<int>(above - section.y_m.begin()) - 1, 0, g.ny - 1);
      eta = (y - section.y_m[static_cast<std::size_t>(j)]) / section.dy_m[static_cast<std::size_t>(j)];
    } else {
      const double fy = (y + 0.5 * o.width_m) / (o.width_m / g.ny);
      j = std::clamp(static_cast<int>(std::floor(fy)), 0, g.ny - 1);
      eta = fy - j;
    }
    const double xi = fx - i;
    std::vector<std::pair<int, double>> w;
    for (int b = 0; b < 4; ++b) {
      const double weight = ((b & 1) ? xi : 1.0 - xi) * ((b & 2) ? eta : 1.0 - eta);
      if (weight != 0.0)
        w.emplace_back(out.node_dofs[static_cast<std::size_t>(g.node(i + (b & 1), j + (b >> 1), g.nz))][2],
                       -share * weight);
    }
    return w;
  };
  int next_rail_dof = deck_dofs;
  for (std::size_t r = 0; r < o.rail_y_m.size(); ++r) {
    const std::size_t n = rx.size();
    std::vector<int> v(n), rot(n);
    for (std::size_t k = 0; k < n; ++k) {
      v[k] = (k == 0 || k + 1 == n) ? -1 : next_rail_dof++;  // anchored ends, as in bridge-2d
      rot[k] = next_rail_dof++;
    }
    RailLine line = RailLine::from_nodes(fmt::format("rail_{}", r + 1), rx, v, rot);
    for (std::size_t e = 0; e < line.num_elements(); ++e) {
      const double h = rx[e + 1] - rx[e];
      const Matrix4 ke = beam_stiffness(o.rail_EI_Nm2, h), me = beam_consistent_mass(o.rail_mass_kg_per_m, h);
      const auto& d = line.element_dofs[e];
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (d[a] >= 0 && d[b] >= 0) {
            k_track.emplace_back(d[a], d[b], ke(a, b));
            m_track.emplace_back(d[a], d[b], me(a, b));
          }
    }
    for (std::size_t k = 0; k < n; ++k) {
      // The pad's relative displacement: rail minus deck top under it (ground: 0).
      std::vector<std::pair<int, double>> g{{v[k], 1.0}};
      std::vector<const SpanGrid*> under;
      for (const SpanGrid& span : grids)
        if (rx[k] >= span.x0_m - kJointTol_m && rx[k] <= span.x0_m + span.length_m + kJointTol_m)
          under.push_back(&span);
      for (const SpanGrid* span : under) {  // a pad over a joint bears on both span ends
        const auto w = top_point(*span, rx[k], o.rail_y_m[r], 1.0 / static_cast<double>(under.size()));
        g.insert(g.end(), w.begin(), w.end());
      }
      add_link(k_track, g, o.pad_k_N_per_m);
      add_link(c_track, g, o.pad_c_Ns_per_m);
    }
    rails.push_back(std::move(line));
  }

  // ---- damping: Rayleigh on the deck at its beam-theory first bending
  // frequency and max(30 Hz, f3), as bridge-2d; the pads have their dashpots.
  const DeckSectionProperties props = deck_section_properties(o);
  out.section_area_m2 = props.area_m2;
  out.section_I_m4 = props.I_m4;
  out.section_J_m4 = props.torsion_J_m4;
  out.section_polar_m4 = props.polar_m4;
  const double longest = *std::max_element(o.spans_m.begin(), o.spans_m.end());
  const double f1 = simply_supported_frequency_hz(longest, o.E_Pa * out.section_I_m4,
                                                   o.density_kg_per_m3 * out.section_area_m2);
  const RayleighCoefficients ray = rayleigh_coefficients(o.damping_ratio, f1, std::max(30.0, 9.0 * f1));

  SparseMatrix K = K_deck + to_sparse(n_total, k_track);
  SparseMatrix M = M_deck + to_sparse(n_total, m_track);
  SparseMatrix C = ray.a1_s * K_deck + ray.a0_per_s * M_deck + to_sparse(n_total, c_track);
  kd = {};

  // ---- output points: soffit centre at each midspan
  std::vector<OutputPoint> outputs;
  for (std::size_t s = 0; s < grids.size(); ++s) {
    const SpanGrid& g = grids[s];
    const int node = g.node(g.nx / 2, g.ny / 2, 0);
    outputs.push_back({fmt::format("span{}_mid", s + 1), out.node_m[static_cast<std::size_t>(node)][0],
                       out.node_dofs[static_cast<std::size_t>(node)][2]});
  }

  StructureInfo info;
  info.source = "deck-3d";
  info.bridge_start_m = 0.0;
  info.bridge_end_m = total;
  info.first_frequency_hz = f1;
  info.deck_dofs = deck_dofs;
  info.track_dofs = n_total - deck_dofs;
  info.damping_ratio = o.damping_ratio;
  info.damping_source = "given";
  info.support_x_m.push_back(0.0);
  for (const double L : o.spans_m) info.support_x_m.push_back(info.support_x_m.back() + L);
  out.model = std::make_shared<const StructureModel>(std::move(K), std::move(M), std::move(C), std::move(rails),
                                                     std::move(outputs), std::move(info));
  return out;
}

}  // namespace railvsi
