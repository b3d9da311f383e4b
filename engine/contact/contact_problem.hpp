#pragma once
// The small nonlinear problem left after condensing the structure and the
// vehicles (Neves et al. (2014), Eng. Struct. 69, section 3.2): find the contact forces P with
//   delta(P) = delta_bar - A P
//   compliant contact:  P_c = H_c(delta_c(P))
//   rigid (bilateral):  delta_c(P) = 0
// by a semi-smooth Newton method on Phi(P) = 0, every component in newtons:
//   compliant: Phi_c = P_c - H_c(delta_c)
//   rigid:     Phi_c = -delta_c / A_cc
// A unilateral compliant law has H = 0 for an open contact, so contacts
// open and close inside the iteration (the active set follows from the
// branch of H). A rigid contact is always bilateral (contact_laws.cpp); A
// then carries the terms of the wheel following the rail and is not
// symmetric (simulation/rigid_wheels.hpp).
#include <vector>

#include "contact/contact_law.hpp"
#include "core/status.hpp"
#include "core/types.hpp"

namespace railvsi {

struct ContactProblemOptions {
  int max_iterations = 50;
  double tolerance = 1e-10;    // on |Phi| / force_scale
  double force_scale_N = 1.0;  // |static wheel loads|
};

struct ContactProblemSummary {
  int iterations = 0;
  double relative_residual = 0.0;
};

// Scratch reused from step to step (no allocation inside the time loop).
struct ContactWorkspace {
  Vector delta, phi, dP, P_trial, phi_trial;
  DenseMatrix J;
  Eigen::PartialPivLU<DenseMatrix> lu;
};

// Residual Phi(P) and, if J is non-null, its generalized Jacobian.
void contact_residual(const Vector& delta_bar, const DenseMatrix& A,
                      const std::vector<const ContactLaw*>& laws, const Vector& P, Vector& delta,
                      Vector& phi, DenseMatrix* J);

// P holds the initial guess on entry and the solution on exit. A must
// already include the (1+alpha) factor of HHT.
Status solve_contact_problem(const Vector& delta_bar, const DenseMatrix& A,
                             const std::vector<const ContactLaw*>& laws,
                             const ContactProblemOptions& options, Vector& P,
                             ContactWorkspace& ws, ContactProblemSummary& summary);

}  // namespace railvsi
