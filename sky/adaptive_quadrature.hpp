#pragma once
// One-dimensional adaptive Gauss–Kronrod quadrature with breakpoints (GSL's QAGP), for the sky
// integrals that reduce to nested 1-D integrals (cie_sky.cpp over caps, perez_sky.cpp's
// normalisation).

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace daylit {

// Adaptive Gauss–Kronrod (21 points) with breakpoints, on a GSL workspace owned here.
class Qagp {
 public:
  Qagp() : workspace_(gsl_integration_workspace_alloc(kIntervals), gsl_integration_workspace_free) {
    if (!workspace_) throw std::bad_alloc();
  }
  // ∫ f over [points.front(), points.back()] with the inner points as breakpoints.
  template <class F>
  std::pair<double, double> integrate(F& f, std::vector<double> points, double relative, double absolute) {
    gsl_function g{[](double x, void* p) { return (*static_cast<F*>(p))(x); }, &f};
    double value = 0, error = 0;
    status_ = gsl_integration_qagp(&g, points.data(), points.size(), absolute, relative, kIntervals, workspace_.get(),
                                   &value, &error);
    return {value, error};
  }
  int status() const noexcept { return status_; }

 private:
  static constexpr std::size_t kIntervals = 2000;
  std::unique_ptr<gsl_integration_workspace, void (*)(gsl_integration_workspace*)> workspace_;
  int status_ = 0;
};

}  // namespace daylit
