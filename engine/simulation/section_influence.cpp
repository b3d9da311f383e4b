#include "simulation/section_influence.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "solver/cholmod_operator.hpp"

namespace railvsi {
namespace {

CholmodOperator static_stiffness(const StructureModel& structure) {
  CholmodOperatorOptions options;
  options.rail_flexibility = false;
  return CholmodOperator(structure, EffectiveMatrixFactors{0.0, 0.0, 1.0}, options);
}

}  // namespace

SectionInfluence::SectionInfluence(const StructureModel& structure, std::vector<int> rail_lines)
    : SectionInfluence(structure, std::move(rail_lines), static_stiffness(structure)) {}

SectionInfluence::SectionInfluence(const StructureModel& structure, std::vector<int> rail_lines,
                                   const StructureOperator& static_K)
    : structure_(structure), rail_lines_(std::move(rail_lines)), forms_(make_section_forms(structure)) {
  if (rail_lines_.empty()) rail_lines_ = {0};
  for (int r : rail_lines_)
    if (r < 0 || r >= static_cast<int>(structure_.rails().size()))
      throw InputError("/analysis/contact/rail_lines", fmt::format("rail line {} does not exist", r));
  auto ws = static_K.make_workspace();
  for (const LinearForm& f : forms_.forms) {
    Vector c = Vector::Zero(structure_.num_dofs());
    for (const auto& [d, v] : f.u) c[d] += v;
    Vector g = Vector::Zero(structure_.num_dofs());
    const Status st = static_K.solve(c, g, *ws);
    if (!st.ok()) throw InputError("/structure", "static influence line of a section force: " + st.message());
    form_influence_.push_back(std::move(g));
  }
}

// c.u with K u = -N^T for a unit load located by `row`, plus the load's own
// term when it stands on the deck line itself (`on_deck`, element -1 if not).
double SectionInfluence::form_value_at(std::size_t form, const RailContactRow& row, const DeckPoint& at) const {
  const Vector& g = form_influence_[form];
  double value = 0.0;
  for (int i = 0; i < 4; ++i)
    if (row.dof[i] >= 0) value -= row.weight[i] * g[row.dof[i]];
  if (at.element >= 0) value += forms_.forms[form].unit_load_value(at);
  return value;
}

DeckPoint SectionInfluence::on_deck(int rail, double x_m) const {
  return forms_.rail_is_deck[static_cast<std::size_t>(rail)] ? deck_point(structure_.info().deck_line, x_m)
                                                             : DeckPoint{};
}

double SectionInfluence::unit_form_value(int form, int rail, double x_m) const {
  const auto row = structure_.rails()[static_cast<std::size_t>(rail)].locate_weights(x_m);
  if (!row) return 0.0;
  return form_value_at(static_cast<std::size_t>(form), *row, on_deck(rail, x_m));
}

double SectionInfluence::unit_form_value(int form, double x_m) const {
  double value = 0.0;
  for (int r : rail_lines_) value += unit_form_value(form, r, x_m);
  return value / static_cast<double>(rail_lines_.size());
}

void SectionInfluence::add_form_values(int rail, double x_m, double scale, std::vector<double>& values) const {
  const auto row = structure_.rails()[static_cast<std::size_t>(rail)].locate_weights(x_m);
  if (!row) return;
  const DeckPoint at = on_deck(rail, x_m);
  for (std::size_t f = 0; f < forms_.forms.size(); ++f) values[f] += scale * form_value_at(f, *row, at);
}

std::size_t SectionInfluence::memory_bytes() const {
  return sizeof(*this) + form_influence_.size() * static_cast<std::size_t>(structure_.num_dofs()) * sizeof(double);
}

}  // namespace railvsi
