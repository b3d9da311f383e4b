#pragma once
// Vertical track irregularity r(x): a positive r raises the rail top. Held as
// samples, linearly interpolated; zero outside the sampled range.
#include <string>
#include <vector>

namespace railvsi {

class Irregularity {
 public:
  // Throws InputError (path relative to the irregularity document) unless x
  // increases strictly and the two lists have the same length (>= 2).
  Irregularity(std::vector<double> x_m, std::vector<double> r_m, std::string source = {});

  double at(double x_m) const;
  const std::vector<double>& x_m() const { return x_; }
  const std::vector<double>& r_m() const { return r_; }
  const std::string& source() const { return source_; }

 private:
  std::vector<double> x_, r_;
  std::string source_;
};

}  // namespace railvsi
