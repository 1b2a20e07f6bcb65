#pragma once
// The one Gauss–Kronrod rule of the kernels: the 7-point Gauss / 15-point Kronrod pair of QUADPACK
// (Piessens, de Doncker-Kapenga, Überhuber and Kahaner 1983, routine qk15), over any real type
// of real_vector.hpp, for the adaptive arc integrals that have no closed form
// (irradiance_gradient.cpp). GSL's QAGP, where sky/ integrates in double, is the same family.

#include <algorithm>
#include <array>

#include "illumination/real_vector.hpp"

namespace daylit::quadrature {

// Gauss–Kronrod 7/15 on [−1, 1], QUADPACK's tables to 33 digits: Kronrod nodes x_k, k = 0..7
// (x_7 = 0; the odd ones are the Gauss nodes), their Kronrod weights, and the Gauss weights of
// x_1, x_3, x_5, x_7. tests/illumination/test_quadrature_rules.cpp checks them against the Gauss–Legendre rule
// and exact integrals of polynomials.
inline constexpr long double kXgk[8] = {0.991455371120812639206854697526329L, 0.949107912342758524526189684047851L,
                                        0.864864423359769072789712788640926L, 0.741531185599394439863864773280788L,
                                        0.586087235467691130294144845693013L, 0.405845151377397166906606412076961L,
                                        0.207784955007898467600689403773245L, 0.0L};
inline constexpr long double kWgk[8] = {0.022935322010529224963732008058970L, 0.063092092629978553290700663189204L,
                                        0.104790010322250183839876322541518L, 0.140653259715525918745189590510238L,
                                        0.169004726639267902826583426598550L, 0.190350578064785409913256402421014L,
                                        0.204432940075298892414161999234649L, 0.209482141084727828012999174891714L};
inline constexpr long double kWg[4] = {0.129484966168869693270611432679082L, 0.279705391489276667901467771423780L,
                                       0.381830050505118944950369775488975L, 0.417959183673469387755102040816327L};

// ∫ f over one panel by the 15-point Kronrod rule, with ∫|f| by the same rule and QUADPACK's
// estimate of the rule's error.
template <class R>
struct KronrodPanel {
  R integral, magnitude, error;
};

// K15 on [a, b] (f called at a + h(1 ± x_k), h = (b − a)/2, in R) with QUADPACK's error estimate (qk15): with resasc = ∫|f − mean|, the error is
// resasc·min(1, (200 |K15 − G7| / resasc)^1.5), which tracks the K15 rule's own error for smooth f
// (|K15 − G7| is the far larger error of G7).
template <class R, class F>
KronrodPanel<R> gauss_kronrod_15(const F& f, R a, R b) {
  const R c = (a + b) / 2, h = (b - a) / 2;
  R kronrod = 0, gauss = 0, magnitude = 0;
  std::array<R, 15> values;
  for (int k = 0; k < 8; ++k) {
    const R x = R(kXgk[k]) * h;
    const R f1 = f(c - x), f2 = k == 7 ? R(0) : f(c + x);
    values[std::size_t(2 * k)] = f1;
    if (k < 7) values[std::size_t(2 * k + 1)] = f2;
    const R sum = f1 + f2;
    kronrod += R(kWgk[k]) * sum;
    magnitude += R(kWgk[k]) * (real::abs(f1) + real::abs(f2));
    if (k % 2 == 1) gauss += R(kWg[k / 2]) * sum;
  }
  const R mean = kronrod / 2;
  R resasc = 0;
  for (int k = 0; k < 8; ++k)
    resasc += R(kWgk[k]) * (real::abs(values[std::size_t(2 * k)] - mean) + (k < 7 ? real::abs(values[std::size_t(2 * k + 1)] - mean) : R(0)));
  R error = real::abs((kronrod - gauss) * h);
  resasc *= h;
  if (resasc > 0 && error > 0) {
    const R ratio = R(200) * error / resasc;
    error = resasc * std::min(R(1), ratio * real::sqrt(ratio));
  }
  return {kronrod * h, magnitude * h, error};
}


}  // namespace daylit::quadrature
