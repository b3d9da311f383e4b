#pragma once
// cos(2*pi*t) and sin(2*pi*t) of an angle t given in turns, computed with
// +, -, *, floor and constants only, in a fixed order: the result is the same
// bit for bit on every IEEE 754 machine that evaluates doubles without excess
// precision or fused multiply-adds (this file and its users are compiled with
// -ffp-contract=off, see engine/CMakeLists.txt). std::cos is not: libm
// implementations round differently. Absolute error below 1e-15.
namespace railvsi {

struct CosSin {
  double cos = 1.0;
  double sin = 0.0;
};

CosSin cos_sin_turns(double t);

}  // namespace railvsi
