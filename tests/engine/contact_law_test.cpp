// Contact laws are created by one factory from their name and options, and
// each answers for itself (force, stiffness, statics, unilateral, name).
#include <cmath>

#include <gtest/gtest.h>

#include "contact/contact_law.hpp"
#include "core/input_error.hpp"

namespace railvsi {
namespace {

ContactOptions options(const char* law) {
  ContactOptions o;
  o.law = law;
  o.hertz_G = 4.0e-8;
  return o;
}

TEST(ContactLawFactory, CreatesEveryLawByItsName) {
  for (const std::string& name : contact_law_names()) {
    ContactOptions o = options(name.c_str());
    const auto law = make_contact_law(o);
    ASSERT_TRUE(law) << name;
    EXPECT_EQ(law->name(), name);
    EXPECT_EQ(law->at_static_load(1e5)->name(), name);
  }
  EXPECT_EQ(contact_law_names(), (std::vector<std::string>{"hertz", "linear-hertz", "rigid"}));
}

TEST(ContactLawFactory, RefusesAnUnknownNameWithItsPath) {
  try {
    (void)make_contact_law(options("coulomb"));
    FAIL() << "an unknown law was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/analysis/contact/law");
    EXPECT_NE(std::string(e.what()).find("coulomb"), std::string::npos);
  }
}

TEST(ContactLawFactory, EachLawChecksItsUnilateralOption) {
  ContactOptions hertz = options("hertz");
  hertz.unilateral = false;
  ContactOptions rigid = options("rigid");
  rigid.unilateral = true;
  for (const ContactOptions& o : {hertz, rigid}) {
    try {
      (void)make_contact_law(o);
      FAIL() << o.law << " accepted a unilateral flag it cannot honour";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "/analysis/contact/unilateral");
    }
  }
  ContactOptions linear = options("linear-hertz");
  EXPECT_TRUE(make_contact_law(linear)->unilateral());  // default
  linear.unilateral = false;
  EXPECT_FALSE(make_contact_law(linear)->unilateral());
  EXPECT_TRUE(make_contact_law(options("hertz"))->unilateral());
  EXPECT_FALSE(make_contact_law(options("rigid"))->unilateral());
}

TEST(ContactLawFactory, HertzForceAndItsInverseFollowTheClosedForm) {
  // n = 2 wheels, G = 4e-8 m/N^(2/3): P = 2 (delta/G)^(3/2).
  const auto hertz = make_contact_law(options("hertz"));
  const double delta = 1.0e-4;
  const double P = 2.0 * std::pow(delta / 4.0e-8, 1.5);
  EXPECT_NEAR(hertz->force(delta), P, 1e-9 * P);
  EXPECT_NEAR(hertz->compression(P), delta, 1e-15);
  EXPECT_NEAR(hertz->stiffness(delta), 1.5 * P / delta, 1e-9 * P / delta);
  EXPECT_NEAR(hertz->compliance(P), delta / (1.5 * P), 1e-9 * delta / P);
  EXPECT_EQ(hertz->force(-1e-6), 0.0);
  // Sharing the wheel between two rails halves n.
  const auto two_rails = make_contact_law(options("hertz"), {0.46, 2});
  EXPECT_NEAR(two_rails->force(delta), 0.5 * P, 1e-9 * P);
}

TEST(ContactLawFactory, LinearHertzIsHertzTangentAtTheStaticLoad) {
  const auto hertz = make_contact_law(options("hertz"));
  ContactOptions o = options("linear-hertz");
  o.unilateral = false;
  const double P0 = 8.0e4;
  const auto linear = make_contact_law(o)->at_static_load(P0);
  const double d0 = hertz->compression(P0);
  EXPECT_NEAR(linear->force(d0), P0, 1e-9 * P0);
  EXPECT_NEAR(linear->stiffness(d0), hertz->stiffness(d0), 1e-9 * hertz->stiffness(d0));
  // Bilateral: pulls below zero compression along the same line.
  const double k = hertz->stiffness(d0);
  EXPECT_NEAR(linear->force(-d0), P0 - 2.0 * k * d0, 1e-9 * P0);
  EXPECT_LT(linear->force(-d0), 0.0);
}

TEST(ContactLawFactory, RigidIsAConstraintWithoutCompression) {
  const auto rigid = make_contact_law(options("rigid"));
  EXPECT_TRUE(rigid->is_constraint());
  EXPECT_FALSE(make_contact_law(options("hertz"))->is_constraint());
  EXPECT_EQ(rigid->compression(1e5), 0.0);
  EXPECT_EQ(rigid->compliance(1e5), 0.0);
}

}  // namespace
}  // namespace railvsi
