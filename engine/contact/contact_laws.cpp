// The contact laws and their factory. Each law is a small immutable class;
// adding one means a class and a line in kLaws below (and the schema enum).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contact/contact_law.hpp"
#include "core/input_error.hpp"

namespace railvsi {
namespace {

// Hertz: P = n (delta/G)^(3/2) for delta > 0, else 0. Always unilateral.
class HertzLaw : public ContactLaw {
 public:
  HertzLaw(double G, double n) : G_(G), n_(n) {}
  std::string_view name() const override { return "hertz"; }
  bool unilateral() const override { return true; }
  double force(double d) const override { return d > 0.0 ? n_ * std::pow(d / G_, 1.5) : 0.0; }
  double stiffness(double d) const override { return d > 0.0 ? 1.5 * n_ * std::sqrt(d / G_) / G_ : 0.0; }
  double compression(double P) const override { return P > 0.0 ? G_ * std::pow(P / n_, 2.0 / 3.0) : 0.0; }
  double compliance(double P) const override {
    return P > 0.0 ? (2.0 / 3.0) * G_ * std::pow(n_, -2.0 / 3.0) * std::pow(P, -1.0 / 3.0) : 0.0;
  }
  std::shared_ptr<const ContactLaw> at_static_load(double) const override {
    return std::make_shared<HertzLaw>(*this);
  }

 protected:
  double G_, n_;
};

// Linear Hertz: P = P0 + k (delta - delta0), Hertz's tangent at the static
// load P0. Statics use the Hertz curve (the two coincide at P0).
class LinearHertzLaw final : public HertzLaw {
 public:
  LinearHertzLaw(double G, double n, bool unilateral, double P0 = 0.0)
      : HertzLaw(G, n), unilateral_(unilateral), P0_(P0), delta0_(compression(P0)),
        k_(delta0_ > 0.0 ? 1.5 * P0 / delta0_ : 0.0) {}
  std::string_view name() const override { return "linear-hertz"; }
  bool unilateral() const override { return unilateral_; }
  double force(double d) const override {
    const double P = P0_ + k_ * (d - delta0_);
    return unilateral_ ? std::max(0.0, P) : P;
  }
  double stiffness(double d) const override {
    return (!unilateral_ || P0_ + k_ * (d - delta0_) > 0.0) ? k_ : 0.0;
  }
  std::shared_ptr<const ContactLaw> at_static_load(double P0) const override {
    return std::make_shared<LinearHertzLaw>(G_, n_, unilateral_, P0);
  }

 private:
  bool unilateral_;
  double P0_, delta0_, k_;
};

// Rigid: delta = 0, the wheel follows the rail. Bilateral by definition: a
// wheel that would need a tensile force keeps it (the run reports it).
class RigidLaw final : public ContactLaw {
 public:
  std::string_view name() const override { return "rigid"; }
  bool unilateral() const override { return false; }
  bool is_constraint() const override { return true; }
  double force(double) const override { return 0.0; }
  double stiffness(double) const override { return 0.0; }
  double compression(double) const override { return 0.0; }
  double compliance(double) const override { return 0.0; }
  std::shared_ptr<const ContactLaw> at_static_load(double) const override {
    return std::make_shared<RigidLaw>(*this);
  }
};

using Maker = std::shared_ptr<const ContactLaw> (*)(const ContactOptions&, const WheelContactData&);

double hertz_n(const ContactOptions& o, const WheelContactData& w) {
  return o.wheels_per_contact / static_cast<double>(std::max(1, w.rails_per_wheel));
}

struct LawEntry {
  const char* name;
  Maker make;
};

const LawEntry kLaws[] = {
    {"hertz",
     [](const ContactOptions& o, const WheelContactData& w) -> std::shared_ptr<const ContactLaw> {
       if (o.unilateral == false)
         throw InputError("/analysis/contact/unilateral", "the Hertz law is unilateral: it cannot pull the wheel");
       return std::make_shared<HertzLaw>(hertz_constant(o, w.radius_m), hertz_n(o, w));
     }},
    {"linear-hertz",
     [](const ContactOptions& o, const WheelContactData& w) -> std::shared_ptr<const ContactLaw> {
       return std::make_shared<LinearHertzLaw>(hertz_constant(o, w.radius_m), hertz_n(o, w),
                                               o.unilateral.value_or(true));
     }},
    {"rigid",
     [](const ContactOptions& o, const WheelContactData&) -> std::shared_ptr<const ContactLaw> {
       if (o.unilateral == true)
         throw InputError("/analysis/contact/unilateral",
                          "a rigid contact is bilateral: the wheel follows the rail and a wheel that "
                          "would lift off keeps a tensile force (reported as tensile_contact). Use "
                          "\"hertz\" to let wheels lose contact");
       return std::make_shared<RigidLaw>();
     }},
};

}  // namespace

double hertz_constant(const ContactOptions& c, double wheel_radius_m) {
  if (c.hertz_G) return *c.hertz_G;
  return 3.86e-8 * std::pow(wheel_radius_m, -0.115);
}

std::shared_ptr<const ContactLaw> make_contact_law(const ContactOptions& options, const WheelContactData& wheel) {
  for (const LawEntry& e : kLaws)
    if (options.law == e.name) return e.make(options, wheel);
  throw InputError("/analysis/contact/law",
                   fmt::format("unknown contact law '{}' (known: {})", options.law, fmt::join(contact_law_names(), ", ")));
}

std::vector<std::string> contact_law_names() {
  std::vector<std::string> names;
  for (const LawEntry& e : kLaws) names.emplace_back(e.name);
  return names;
}

}  // namespace railvsi
