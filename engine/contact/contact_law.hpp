#pragma once
// Normal wheel-rail contact law, P = H(delta), delta > 0 compression: one
// small immutable class per law behind one interface (Ceres' LossFunction is
// the model), created by make_contact_law from the scene's options. Adding a
// law means one class and one line of the factory table in contact_laws.cpp,
// plus its name in schemas/analysis.schema.json.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace railvsi {

struct ContactOptions {
  // A name of contact_law_names(): "hertz", "linear-hertz", "rigid".
  std::string law = "hertz";
  // A unilateral contact may open (P = 0) and close again; a bilateral one
  // holds the wheel on the rail whatever the sign of the force. Absent: the
  // law's default (only linear-hertz offers the choice).
  std::optional<bool> unilateral;
  // Hertz constant G in m/N^(2/3); when absent, from the wheel radius:
  // G = 3.86e-8 * R^-0.115 (conical tread, as cited from Zhai's vehicle-track
  // coupled dynamics; unverified against a primary source).
  std::optional<double> hertz_G;
  // Wheels sharing one contact of the model (2 for a plane model lumping
  // both rails): P = n * (delta/G)^(3/2).
  double wheels_per_contact = 2.0;
  // Rail lines every wheel (and every moving force) bears on. A plane train
  // on a 3D deck with two rails lists both: each wheelset then makes one
  // contact per rail, sharing wheels_per_contact between them, and a moving
  // force is split equally between the rails.
  std::vector<int> rail_lines{0};
};

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  virtual std::string_view name() const = 0;
  // A unilateral law never returns a tensile force.
  virtual bool unilateral() const = 0;
  // True for a displacement constraint (rigid): delta = 0 while in contact,
  // the wheel follows the rail (simulation/rigid_wheels.hpp) and force(),
  // stiffness() do not apply; the force comes from the wheel's equilibrium.
  virtual bool is_constraint() const { return false; }
  // Force and its derivative dP/d(delta) for a compliant law.
  virtual double force(double delta_m) const = 0;
  virtual double stiffness(double delta_m) const = 0;
  // Compression under a given load (static equilibrium, the inverse law) and
  // its derivative d(delta)/dP; 0 for a constraint.
  virtual double compression(double P_N) const = 0;
  virtual double compliance(double P_N) const = 0;
  // The law a run uses for a wheel whose static load is P0 (linear-hertz is
  // linearized there; the others are independent of it).
  virtual std::shared_ptr<const ContactLaw> at_static_load(double P0_N) const = 0;
};

// What a law may need to know of the wheel and of the model's contacts.
struct WheelContactData {
  double radius_m = 0.46;
  int rails_per_wheel = 1;  // contacts the wheel's load is shared between
};

// Throws InputError with the JSON path under /analysis/contact for an
// unknown name or options the law does not admit.
std::shared_ptr<const ContactLaw> make_contact_law(const ContactOptions& options,
                                                   const WheelContactData& wheel = {});
std::vector<std::string> contact_law_names();

// G of the Hertz law for a wheel of this radius.
double hertz_constant(const ContactOptions& c, double wheel_radius_m);

}  // namespace railvsi
