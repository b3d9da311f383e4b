#pragma once
// Vertical track irregularity r(x): a positive r raises the rail top. Held as
// samples, linearly interpolated; zero outside the sampled range.
// Rigid contact makes the wheel follow the profile exactly, so it needs the
// profile's slope and curvature: for it, smooth_at() interpolates the same
// samples with a natural cubic spline (C2: a finite wheel acceleration
// V^2 r'' where linear interpolation would give impulses at every sample).
#include <string>
#include <vector>

namespace railvsi {

struct ProfilePoint {
  double r_m = 0.0;
  double slope = 0.0;             // dr/dx
  double curvature_per_m = 0.0;   // d2r/dx2
};

class Irregularity {
 public:
  // Throws InputError (path relative to the irregularity document) unless x
  // increases strictly and the two lists have the same length (>= 2).
  Irregularity(std::vector<double> x_m, std::vector<double> r_m, std::string source = {});

  double at(double x_m) const;
  // The same value; `hint` (the caller's, per wheel: the model is shared)
  // is the sample interval of the last call, tried before the binary
  // search, since a wheel moves by less than a sample per step.
  double at(double x_m, std::size_t& hint) const;
  ProfilePoint smooth_at(double x_m) const;
  const std::vector<double>& x_m() const { return x_; }
  const std::vector<double>& r_m() const { return r_; }
  const std::string& source() const { return source_; }

 private:
  // r at x (x_[j-1] <= x < x_[j]; j past the end: the last sample's).
  double interpolated(std::size_t j, double x) const;
  std::vector<double> x_, r_;
  std::vector<double> spline_m_;  // second derivatives of the natural cubic spline at the samples
  std::string source_;
};

}  // namespace railvsi
