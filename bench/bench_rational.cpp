// `daylit bench rational`: the approximate paths of the rational moments beside the exact ones
// (DESIGN.md §6).
//
// rational_special_functions.csv/.png: Cl2 by GSL, by Grosjean's formula (Chen and Arvo 2000,
//   eq. 39) and by our long double series, and Λ(α, β) by eq. 36 with each of them and by the
//   tabulated Λ' (eqs. 40–45) at three grid sizes: time per evaluation against the maximum and RMS
//   error (absolute for Cl2, relative for Λ) over seeded random arguments, against __float128
//   references (the series of clausen.hpp).
// rational_moments_error_vs_time.csv/.png and rational_cost_per_edge.png: τ^{n,1,1;1} (the glossy
//   reflection of a linearly varying luminaire) by the exact O(n²) path and the semi-analytic one
//   (Gauss–Legendre of T3 with 4 ... 128 nodes) for n = 1 ... 1000 on a 4-edge and a 16-edge
//   luminaire: time per evaluation, ns per edge, error against the semi-analytic path with 512
//   nodes (checked against quadrature of the surface integral in tests/illumination/test_rational_moments.cpp),
//   each path's own error estimate and the precision it settled in; with adaptive cubature over
//   the sphere (spherical_quadrature.hpp) at 1e-4 ... 1e-10 for n ≤ 50 as the 2-D baseline.
// rational_luminaire_degree.csv: polynomial exitance of degree 0 ... 24 on stress geometries: time,
//   error estimate, the condition κ of the double pass and the precision used: where the
//   recurrences (Theorem 4 in w's frame) stop being stable in double.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <gsl/gsl_sf_clausen.h>

#include "bench/bench_suites.hpp"
#include "report/plot.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "illumination/clausen.hpp"
#include "illumination/polynomial_luminaire.hpp"
#include "illumination/rational_moments.hpp"
#include "illumination/spherical_quadrature.hpp"
#include "illumination/xoshiro256.hpp"

namespace daylit::cli {

namespace {


// The precision of the references: __float128 where the compiler has it.
#if DAYLIT_HAVE_FLOAT128
using Reference = real::quad;
#else
using Reference = long double;
#endif

// Thread CPU seconds per call of f, by the one timing scheme (bench/timing.hpp) over `budget`
// seconds in at least 3 batches.
template <class F>
double time_per_call(F&& f, double budget) {
  return bench::cpu_seconds_per_call(
      [&](long) {
        f();
        return 0.0;
      },
      {budget, 3});
}

volatile double sink;  // keeps the timed calls from being optimised away

struct SpecialRow {
  std::string function, method;
  int parameter;
  double seconds, max_error, rms_error;
};

std::vector<SpecialRow> special_functions(bool quick) {
  const int N = quick ? 2000 : 20000;
  const double budget = quick ? 0.01 : 0.2;
  Xoshiro256 rng(20000619);  // the same arguments on every platform (std distributions differ)
  std::vector<double> xs(N), alphas(N), betas(N);
  for (int i = 0; i < N; ++i) {
    xs[i] = rng.uniform(-2 * M_PI, 2 * M_PI);
    alphas[i] = rng.uniform(0.01, 0.999);
    betas[i] = rng.uniform(-1.5707, 1.5707);
  }
  std::vector<SpecialRow> rows;

  // Cl2: absolute error against the __float128 series.
  std::vector<double> cl2_ref(N);
  for (int i = 0; i < N; ++i) cl2_ref[i] = double(clausen(Reference(xs[i])));
  auto cl2_row = [&](const std::string& method, auto&& f) {
    double worst = 0, sum2 = 0;
    for (int i = 0; i < N; ++i) {
      const double e = std::abs(f(xs[i]) - cl2_ref[i]);
      worst = std::max(worst, e);
      sum2 += e * e;
    }
    const double t = time_per_call(
                         [&] {
                           double s = 0;
                           for (int i = 0; i < N; ++i) s += f(xs[i]);
                           sink = s;
                         },
                         budget) /
                     N;
    rows.push_back({"cl2", method, 0, t, worst, std::sqrt(sum2 / N)});
  };
  cl2_row("series", [](double x) { return clausen(x); });
  cl2_row("gsl", [](double x) { return gsl_sf_clausen(x); });
  cl2_row("grosjean", [](double x) { return clausen_grosjean(x); });
  cl2_row("series_long_double", [](double x) { return double(clausen((long double)x)); });

  // Λ(α, β): relative error against eq. 36 in __float128.
  std::vector<double> lambda_ref(N);
  for (int i = 0; i < N; ++i) {
    const Reference a = alphas[i], k = real::sqrt((1 - a) * (1 + a)), b = betas[i];
    lambda_ref[i] = double(lambda_bracket<Reference>(a, k, real::sin(b), real::cos(b)) / (4 * k));
  }
  auto lambda_row = [&](const std::string& method, int parameter, auto&& f) {
    double worst = 0, sum2 = 0;
    for (int i = 0; i < N; ++i) {
      const double e = std::abs(f(alphas[i], betas[i]) - lambda_ref[i]) / std::abs(lambda_ref[i]);
      worst = std::max(worst, e);
      sum2 += e * e;
    }
    const double t = time_per_call(
                         [&] {
                           double s = 0;
                           for (int i = 0; i < N; ++i) s += f(alphas[i], betas[i]);
                           sink = s;
                         },
                         budget) /
                     N;
    rows.push_back({"lambda", method, parameter, t, worst, std::sqrt(sum2 / N)});
  };
  lambda_row("eq36_series", 0, [](double a, double b) { return chen_arvo_lambda(a, b); });
  lambda_row("eq36_grosjean", 0, [](double a, double b) { return chen_arvo_lambda(a, b, ClausenMethod::grosjean); });
  for (const int nodes : quick ? std::vector<int>{100, 300} : std::vector<int>{100, 300, 1000}) {
    const LambdaPrimeTable table(nodes);
    lambda_row("table", nodes, [&](double a, double b) { return table.lambda(a, b); });
  }
  return rows;
}

struct MomentRow {
  int n, edges;
  std::string method;
  double parameter, seconds, error, estimate;
  int precision;
};

// A luminaire polygon with `edges` edges on the plane z = 1.3 (tilted slightly), seen from a
// receiver below it; axes as in tests/illumination/test_rational_moments.cpp.
SphericalRegion luminaire(int edges) {
  std::vector<Vec3> poly;
  for (int i = 0; i < edges; ++i) {
    const double t = 2 * M_PI * (i + 0.5) / edges;
    poly.push_back({0.1 + 0.8 * std::cos(t), -0.1 + 0.7 * std::sin(t), 1.3 + 0.1 * std::cos(t)});
  }
  return directions_through(poly, Vec3{0.3, -0.2, 0});
}

std::vector<MomentRow> moments(bool quick) {
  const Vec3 w = normalized(Vec3{0.2, 0.1, 1}), v = normalized(Vec3{0.3, 0.4, 0.8}), a{1, -0.5, 0.2}, b{-0.3, 0.7, 0.5};
  const double budget = quick ? 0.005 : 0.1;
  const std::vector<int> ns = quick ? std::vector<int>{1, 10, 100} : std::vector<int>{1, 2, 5, 10, 20, 50, 100, 200, 500, 1000};
  const std::vector<int> nodes = quick ? std::vector<int>{8, 32} : std::vector<int>{4, 8, 16, 32, 64, 128};
  std::vector<MomentRow> rows;
  for (const int edges : {4, 16}) {
    const SphericalRegion region = luminaire(edges);
    for (const int n : ns) {
      const double ref = rational_moment_n11(region, v, n, a, b, w, {RationalMethod::semi_analytic, 512}).value;
      auto add = [&](const std::string& method, double parameter, const RationalMomentOptions& o) {
        const RationalMoment m = rational_moment_n11(region, v, n, a, b, w, o);
        const int precision = m.precision;
        const double t = time_per_call([&] { sink = rational_moment_n11(region, v, n, a, b, w, o).value; }, budget);
        rows.push_back({n, edges, method, parameter, t, std::abs(m.value - ref) / std::abs(ref), m.relative_error, precision});
      };
      add("exact", 0, {});
      for (const int p : nodes) add("semi_analytic", p, {RationalMethod::semi_analytic, p});
      if (n <= 50 && edges == 4)
        for (const double tol : quick ? std::vector<double>{1e-4} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10}) {
          auto g = [&](const Vec3& u) { return std::pow(dot(v, u), n) * dot(a, u) * dot(b, u) / dot(w, u); };
          const QuadratureResult q = integrate_over_region(region, g, tol);
          const double t = time_per_call([&] { sink = integrate_over_region(region, g, tol).value; }, budget);
          rows.push_back({n, edges, "cubature", tol, t, std::abs(q.value - ref) / std::abs(ref), q.error_estimate / std::abs(q.value), 0});
        }
    }
  }
  return rows;
}

struct DegreeRow {
  std::string geometry;
  int degree;
  double seconds, estimate, condition;
  int precision;
};

std::vector<DegreeRow> degrees(bool quick) {
  struct Geometry {
    const char* name;
    Vec3 o, n, c0, e1, e2;
  };
  const std::vector<Geometry> geometries = {
      {"tilted_below", {0.3, -0.2, 0}, normalized(Vec3{0.1, 0.2, 1}), {-0.5, -0.7, 1.3}, {1.2, 0, 0.1}, {0.02, 1.1, -0.24}},
      {"receiver_1e-6_from_plane", {0.3, -0.2, 1.3 - 1e-6}, normalized(Vec3{0.1, 0.2, 1}), {-0.5, -0.7, 1.3}, {1.2, 0, 0}, {0, 1.1, 0}},
      {"50_widths_off_axis", {0, 0, 0}, {0, 0, 1}, {50, 0.2, 1}, {1, 0, 0}, {0, 1, 0}},
      {"1e-3_wide_100_away", {0, 0, 0}, {0, 0, 1}, {0.1, 0.2, 100}, {1e-3, 0, 0}, {0, 1e-3, 0}},
  };
  const std::vector<int> ds = quick ? std::vector<int>{0, 2, 6} : std::vector<int>{0, 1, 2, 3, 4, 6, 8, 10, 12, 16};
  std::vector<DegreeRow> rows;
  for (const Geometry& g : geometries) {
    const SphericalRegion region = directions_through({g.c0, g.c0 + g.e1, g.c0 + g.e1 + g.e2, g.c0 + g.e2}, g.o);
    for (const int D : ds) {
      ExitancePolynomial M{{1.0, 0, 0, 0}};
      for (int i = 0; i <= D; ++i)
        for (int j = 0; i + j <= D; ++j) M.push_back({(i + 2 * j) % 3 == 0 ? -0.3 / (1 + i) : 0.7 / (1 + j), i, j, D - i - j});
      const LuminaireIrradiance E = polynomial_luminaire_irradiance(region, g.o, g.n, g.c0, cross(g.e1, g.e2), M);
      const double t = time_per_call(
          [&] { sink = polynomial_luminaire_irradiance(region, g.o, g.n, g.c0, cross(g.e1, g.e2), M).value; },
          quick ? 0.002 : 0.05);
      rows.push_back({g.name, D, t, E.relative_error, E.condition, E.precision});
    }
  }
  return rows;
}

}  // namespace

int run_bench_rational(const BenchOptions& opt) {
  const auto t0 = bench::clock_type::now();
  bench::StatusLine status(!opt.quiet);
  status.show("bench rational: special functions");
  const std::vector<SpecialRow> special = special_functions(opt.quick);
  status.show("bench rational: rational moments, exact and semi-analytic");
  const std::vector<MomentRow> moment_rows = moments(opt.quick);
  status.show("bench rational: polynomial luminaires by degree");
  const std::vector<DegreeRow> degree_rows = degrees(opt.quick);
  status.clear();

  const std::filesystem::path dir(opt.out);
  std::filesystem::create_directories(dir);
  StagedOutputs outputs;
  const std::string special_csv = (dir / "rational_special_functions.csv").string(),
                    special_png = (dir / "rational_special_functions.png").string(),
                    moments_csv = (dir / "rational_moments_error_vs_time.csv").string(),
                    moments_png = (dir / "rational_moments_error_vs_time.png").string(),
                    cost_png = (dir / "rational_cost_per_edge.png").string(),
                    degree_csv = (dir / "rational_luminaire_degree.csv").string();
  {
    std::ofstream f(outputs.stage(special_csv));
    f << "function,method,parameter,time_per_eval_s,max_error,rms_error,error_kind\n";
    for (const SpecialRow& r : special)
      f << fmt::format("{},{},{},{:.4e},{:.3e},{:.3e},{}\n", r.function, r.method, r.parameter, r.seconds, r.max_error,
                       r.rms_error, r.function == "cl2" ? "absolute" : "relative");
    if (!f) throw Error(special_csv + ": cannot write");
  }
  {
    std::ofstream f(outputs.stage(moments_csv));
    f << "n,edges,method,parameter,time_per_eval_s,ns_per_edge,relative_error,relative_error_estimate,precision\n";
    for (const MomentRow& r : moment_rows)
      f << fmt::format("{},{},{},{:g},{:.4e},{:.1f},{:.3e},{:.3e},{}\n", r.n, r.edges, r.method, r.parameter, r.seconds,
                       1e9 * r.seconds / r.edges, r.error, r.estimate, r.precision);
    if (!f) throw Error(moments_csv + ": cannot write");
  }
  {
    std::ofstream f(outputs.stage(degree_csv));
    f << "geometry,degree,time_per_eval_s,relative_error_estimate,double_condition,precision\n";
    for (const DegreeRow& r : degree_rows)
      f << fmt::format("{},{},{:.4e},{:.3e},{:.3e},{}\n", r.geometry, r.degree, r.seconds, r.estimate, r.condition, r.precision);
    if (!f) throw Error(degree_csv + ": cannot write");
  }

  const std::vector<PlotColour> colours = {{0.85f, 0.35f, 0.1f}, {0.15f, 0.35f, 0.75f}, {0.2f, 0.6f, 0.2f},
                                           {0.6f, 0.2f, 0.6f},   {0.5f, 0.5f, 0.5f},    {0.9f, 0.6f, 0.0f}};
  const std::vector<PlotMarker> markers = {PlotMarker::circle, PlotMarker::square, PlotMarker::triangle, PlotMarker::diamond,
                                           PlotMarker::triangle_down, PlotMarker::cross};
  {
    Plot plot;
    plot.title = "Cl2 and Chen and Arvo's Lambda: maximum error against time per evaluation";
    plot.subtitle = "seeded random arguments; references: __float128 series (Cl2 absolute error, Lambda relative error)";
    plot.x_label = "CPU time per evaluation (s)";
    plot.y_label = "maximum error";
    plot.y_floor = 1e-17;
    std::size_t k = 0;
    for (const SpecialRow& r : special) {
      const std::string name = r.function + " " + r.method + (r.parameter ? fmt::format(" {}x{}", r.parameter, r.parameter) : "");
      plot.series.push_back({name, {{r.seconds, r.max_error}}, colours[k % colours.size()], markers[k % markers.size()], false});
      ++k;
    }
    plot.notes = {"Lambda by eq. 36 costs three Cl2; the table costs a bilinear lookup and one atan2 and log (eq. 41)."};
    write_loglog_plot(outputs.stage(special_png), plot);
  }
  {
    Plot plot;
    plot.title = "tau^{n,1,1;1}: exact O(n^2) path and semi-analytic quadrature of T3, error against run time";
    plot.subtitle = "4-edge luminaire; reference: semi-analytic with 512 nodes; one series per n, the exact path as a filled marker";
    plot.x_label = "CPU time per evaluation (s)";
    plot.y_label = "relative error";
    plot.y_floor = 1e-17;
    std::size_t k = 0;
    std::vector<int> ns;
    for (const MomentRow& r : moment_rows)
      if (r.edges == 4 && (ns.empty() || ns.back() != r.n)) ns.push_back(r.n);
    for (const int n : ns) {
      PlotSeries semi{fmt::format("semi-analytic, n = {}", n), {}, colours[k % colours.size()], PlotMarker::circle, true};
      PlotSeries exact{fmt::format("exact, n = {}", n), {}, colours[k % colours.size()], PlotMarker::square, false};
      PlotSeries cub{"", {}, colours[k % colours.size()], PlotMarker::cross, true};
      for (const MomentRow& r : moment_rows) {
        if (r.edges != 4 || r.n != n) continue;
        if (r.method == "semi_analytic") semi.points.push_back({r.seconds, r.error});
        if (r.method == "exact") exact.points.push_back({r.seconds, r.error});
        if (r.method == "cubature") cub.points.push_back({r.seconds, r.error});
      }
      plot.series.push_back(semi);
      plot.series.push_back(exact);
      if (!cub.points.empty()) {
        cub.name = fmt::format("adaptive cubature, n = {}", n);
        plot.series.push_back(cub);
      }
      ++k;
    }
    write_loglog_plot(outputs.stage(moments_png), plot);
  }
  {
    Plot plot;
    plot.title = "Rational moments: cost per edge against n";
    plot.subtitle = "tau^{n,1,1;1} on 4- and 16-edge luminaires; x: n, y: ns per edge";
    plot.x_label = "n (power of the Phong lobe)";
    plot.y_label = "CPU ns per edge";
    std::size_t k = 0;
    for (const int edges : {4, 16})
      for (const std::string method : {"exact", "semi_analytic"}) {
        PlotSeries s{fmt::format("{}{}, {} edges", method, method == "exact" ? "" : " (32 nodes)", edges), {},
                     colours[k % colours.size()], markers[k % markers.size()], true};
        for (const MomentRow& r : moment_rows)
          if (r.edges == edges && r.method == method && (method == "exact" || r.parameter == 32))
            s.points.push_back({double(r.n), 1e9 * r.seconds / r.edges});
        plot.series.push_back(s);
        ++k;
      }
    write_loglog_plot(outputs.stage(cost_png), plot);
  }
  outputs.commit();
  if (!opt.quiet) {
    std::cerr << fmt::format("{:>7} {:>20} {:>6} {:>12} {:>10} {:>10}\n", "", "method", "param", "s/eval", "max err", "rms err");
    for (const SpecialRow& r : special)
      std::cerr << fmt::format("{:>7} {:>20} {:>6} {:>12.3e} {:>10.2e} {:>10.2e}\n", r.function, r.method, r.parameter, r.seconds,
                               r.max_error, r.rms_error);
    std::cerr << fmt::format("\n{:>5} {:>5} {:>14} {:>6} {:>12} {:>10} {:>10} {:>10}\n", "n", "edges", "method", "param",
                             "ns/edge", "error", "estimate", "precision");
    for (const MomentRow& r : moment_rows)
      if (r.method != "cubature")
        std::cerr << fmt::format("{:>5} {:>5} {:>14} {:>6g} {:>12.1f} {:>10.2e} {:>10.2e} {:>10}\n", r.n, r.edges, r.method,
                                 r.parameter, 1e9 * r.seconds / r.edges, r.error, r.estimate, r.precision);
    std::cerr << fmt::format("\n{:>26} {:>6} {:>12} {:>10} {:>10} {:>9}\n", "geometry", "degree", "s/eval", "estimate",
                             "kappa(dbl)", "precision");
    for (const DegreeRow& r : degree_rows)
      std::cerr << fmt::format("{:>26} {:>6} {:>12.3e} {:>10.2e} {:>10.2e} {:>9}\n", r.geometry, r.degree, r.seconds, r.estimate,
                               r.condition, r.precision);
    std::cerr << fmt::format("bench rational: wrote {}, {}, {}, {}, {}, {} ({:.1f} s)\n", special_csv, special_png, moments_csv,
                             moments_png, cost_png, degree_csv, bench::seconds_since(t0));
  }
  return 0;
}

}  // namespace daylit::cli
