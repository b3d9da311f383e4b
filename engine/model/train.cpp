#include "model/train.hpp"

#include <algorithm>

namespace railvsi {

double Train::length_m() const {
  double last = 0.0;
  for (const auto& f : moving_forces) last = std::max(last, f.offset_m);
  for (const auto& v : vehicles)
    for (const auto& w : v.model->wheels()) last = std::max(last, v.offset_m + w.offset_m);
  return last;
}

int Train::num_axles() const {
  std::size_t n = moving_forces.size();
  for (const auto& v : vehicles) n += v.model->wheels().size();
  return static_cast<int>(n);
}

}  // namespace railvsi
