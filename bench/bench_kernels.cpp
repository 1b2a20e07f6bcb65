// `daylit bench kernels`: for each case, the exact closed form, early termination at several
// tolerances, and two Monte Carlo estimators at N = 16 … 65,536 samples, each timed and compared
// with a reference; and the cost per polygon edge of the axial moment as the order grows.
//
// Timing: bench/timing.hpp's one scheme (thread CPU time per evaluation, the best of batches of
// evaluations sized against the target), on one core.
// Reference: the moment by Arvo's eqs. 11 and 14 on the same double directions, evaluated in
// __float128 (long double where the compiler lacks it), with an error estimate from the
// magnitudes of its terms that is reported beside it; the kernels' own accuracy is measured
// against it. Monte Carlo errors are RMS over 8 seeds (seeds 1–8; timings use other seeds).
//
// kernels_error_vs_time.csv, one row per (case, method, parameter): parameter is the tolerance
// (truncated) or N (mc_*); relative_error is |value − reference|/|reference| (RMS over the seeds
// for mc_*); relative_error_bound is the kernel's own estimate 10·u·κ (exact) or the bound it
// returns (truncated); relative_standard_error is the RMS of the estimators' standard errors;
// precision is what the exact kernel escalated to; terms counts the truncated series' terms.
// kernels_cost_per_edge.csv: time per evaluation / edges, and / edges / order.


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "bench/bench_suites.hpp"
#include "report/plot.hpp"
#include "report/progress_bar.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "illumination/arc_edge.hpp"
#include "illumination/moments.hpp"
#include "illumination/monte_carlo.hpp"
#include "illumination/solid_angle.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit::cli {

namespace {

using bench::clock_type;
using bench::seconds_since;

// What a run measures: --quick trims every list and the timing target, not the method set.
struct KernelSuiteSettings {
  double target_seconds;  // per measurement
  int min_batches;
  std::vector<long> samples;
  std::vector<double> tolerances;
  int seeds;
  std::vector<int> edges, orders;
};

KernelSuiteSettings settings_for(bool quick) {
  if (quick) return {0.008, 3, {16, 256, 4096, 65536}, {1e-2, 1e-6, 1e-10, 1e-14}, 8, {4, 16, 64}, {1, 100, 10000}};
  return {0.2, 9, {16, 64, 256, 1024, 4096, 16384, 65536}, {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14}, 8,
          {4, 16, 64}, {1, 10, 100, 1000, 10000}};
}

bench::Repetitions repetitions(const KernelSuiteSettings& s) { return {s.target_seconds, s.min_batches}; }

// ── Cases ───────────────────────────────────────────────────────────────────────────────────

struct KernelCase {
  std::string name;         // CSV key
  std::string label;        // legend
  std::string description;  // CSV
  SphericalRegion region;
  Vec3 w;  // unit
  int n;
  std::optional<Vec3> v;  // double-axis moment ∫(w·u)^n (v·u) dσ when given, else axial ∫(w·u)^n dσ
  int edges;
};

std::vector<Vec3> rectangle_y(double y, double x0, double x1, double z0, double z1) {
  return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
}

std::vector<KernelCase> kernel_cases() {
  const Vec3 desk{0.4, 0, 0.8}, up{0, 0, 1};
  const std::vector<Vec3> window = rectangle_y(3, -1.2, 1.2, 0.9, 2.1);
  const std::vector<Vec3> luminaire{{1.2, 0.7, 2.8}, {1.8, 0.7, 2.8}, {1.8, 1.3, 2.8}, {1.2, 1.3, 2.8}};
  const std::vector<Vec3> l_rooflight{{-1, 1, 3}, {1, 1, 3}, {1, 1.6, 3}, {-0.2, 1.6, 3}, {-0.2, 2.6, 3}, {-1, 2.6, 3}};
  const Vec3 phong_axis = normalized(Vec3{0.3, 0.2, 1});  // −(emission axis): 23° off the receiver
  const Vec3 mirror = normalized(Vec3{0.1, 3, 1.7} - desk);
  std::vector<KernelCase> cases{
      {"window_lambert", "window, Lambert (n=1)",
       "2.4 x 1.2 m window 3 m from a desk point; irradiance from unit radiance, Lambert's integral(n.u) with n = "
       "up (axial moment, n = 1)",
       directions_through(window, desk), up, 1, std::nullopt, 4},
      {"window_overcast", "window, overcast (n=1, v)",
       "same window from a vertical sensor facing it: the CIE overcast sky's gradient term integral(z.u)(n.u) "
       "(double-axis moment, n = 1, w = zenith, v = sensor normal)",
       directions_through(window, desk), up, 1, Vec3{0, 1, 0}, 4},
      {"phong10", "Phong n=10 luminaire",
       "0.6 x 0.6 m Phong luminaire (n = 10) on a 2.8 m ceiling, 23 deg off its axis, on a desk: integral(w.u)^10 "
       "(n.u) (double-axis moment, Arvo 6.1)",
       directions_through(luminaire, {0, 0, 0.8}), phong_axis, 10, up, 4},
      {"phong100", "Phong n=100 luminaire",
       "the same luminaire with Phong exponent 100: integral(w.u)^100 (n.u) (double-axis moment)",
       directions_through(luminaire, {0, 0, 0.8}), phong_axis, 100, up, 4},
      {"glossy1000", "glossy n=1000 reflection",
       "glossy desk (Phong n = 1000) reflecting the window: integral(r.u)^1000 about the mirror direction r, which "
       "falls inside the window (axial moment)",
       directions_through(window, desk), mirror, 1000, std::nullopt, 4},
      {"l_rooflight", "L-shaped rooflight (n=1, v)",
       "non-convex L-shaped rooflight (6 edges) on a 3 m ceiling from a sensor tilted 30 deg: the overcast term "
       "integral(z.u)(n.u) (double-axis moment, n = 1)",
       directions_through(l_rooflight, desk), up, 1, Vec3{0, 0.5, std::sqrt(0.75)}, 6},
  };
  return cases;
}

// ── Reference ───────────────────────────────────────────────────────────────────────────────

#if DAYLIT_HAVE_FLOAT128
using Ref = real::quad;
constexpr const char* kReferenceName = "Arvo eqs. 11/14 in __float128";
constexpr double kReferenceRoundoff = 0x1p-113;
#else
using Ref = long double;
constexpr const char* kReferenceName = "Arvo eqs. 11/14 in long double";
constexpr double kReferenceRoundoff = 0x1p-64;
#endif

struct Reference {
  double value;
  double relative_error;  // estimate: 10 u Σ|terms| / |value|, the arcs' terms counted at their bound θ
};

// Arvo's eq. 11 (axial) or eq. 14 (double-axis) with the forward recurrences, in Ref:
//     G_0 = θ, G_1 = X sin θ + β (1 − cos θ), k G_k = X^{k−1} β − Y^{k−1} γ + (k − 1) c² G_{k−2}
// on each arc (X = w·a, Y = w·b, β, γ the tangent components), then
//     (k + 1) τ^k = (k − 1) |w|² τ^{k−2} + Σ (w·m) G_{k−1},   (n + 2) τ^{n,1} = n (w·v) τ^{n−1} + Σ (v·m) G_n.
// The upward recurrence for G keeps its absolute error at the scale of θ, which the error estimate
// accounts for; in 113 bits that is far below the double results it judges.
Reference reference_moment(const KernelCase& c) {
  using real::Tracked;
  const int n = c.n;
  const bool double_axis = c.v.has_value();
  const real::V3<Ref> w(c.w), v(c.v.value_or(Vec3{}));
  // Each sum with the sum of its terms' magnitudes (tracked_sum.hpp), an arc's terms counted at
  // their bound |w·m| θ.
  std::vector<Tracked<Ref>> boundary(std::size_t(std::max(n, 1)));
  Tracked<Ref> boundary_v, sigma;
  const int k_max = double_axis ? n : n - 1;
  std::vector<Ref> G(std::size_t(std::max(k_max, 0)) + 1);
  for (const auto& loop : c.region.loops) {
    for_each_solid_angle_term<Ref>(loop, [&](Ref t) { sigma.add(t); });
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const auto arc = arc_edge(real::V3<Ref>(loop[i]), real::V3<Ref>(loop[(i + 1) % loop.size()]));
      if (!arc) continue;
      const Ref X = dot(w, arc->start), Y = dot(w, arc->end), beta = dot(w, arc->start_tangent),
                gamma = dot(w, arc->end_tangent), c2 = X * X + beta * beta;
      G[0] = arc->length;
      if (k_max >= 1) G[1] = X * arc->sin_length + beta * arc->one_minus_cos;
      Ref Xp = X, Yp = Y;
      for (int k = 2; k <= k_max; ++k) {
        G[std::size_t(k)] = (Xp * beta - Yp * gamma + Ref(k - 1) * c2 * G[std::size_t(k) - 2]) / Ref(k);
        Xp *= X;
        Yp *= Y;
      }
      const Ref wm = dot(w, arc->normal);
      for (int k = 0; k < n; ++k) boundary[std::size_t(k)].add(wm * G[std::size_t(k)], real::abs(wm) * arc->length);
      if (double_axis) {
        const Ref vm = dot(v, arc->normal);
        boundary_v.add(vm * G[std::size_t(n)], real::abs(vm) * arc->length);
      }
    }
  }
  const int top = double_axis ? n - 1 : n;  // highest axial order needed
  const Ref w2 = dot(w, w);                   // not 1 for a normalised double: it matters at high orders
  std::vector<Tracked<Ref>> tau(std::size_t(std::max(top, 0)) + 1);
  tau[0] = sigma;
  for (int k = 1; k <= top; ++k) {
    const Tracked<Ref> lower = k >= 2 ? tau[std::size_t(k) - 2] : Tracked<Ref>{};
    tau[std::size_t(k)] = (Ref(k - 1) * w2 * lower + boundary[std::size_t(k) - 1]) / Ref(k + 1);
  }
  Tracked<Ref> result;
  if (!double_axis) {
    result = tau[std::size_t(n)];
  } else {
    const Tracked<Ref> lower = n > 0 ? tau[std::size_t(n) - 1] : Tracked<Ref>{};
    result = (Ref(n) * dot(w, v) * lower + boundary_v) / Ref(n + 2);
  }
  return {double(result.value), 10 * kReferenceRoundoff * double(real::condition(result))};
}

// ── Measurements ────────────────────────────────────────────────────────────────────────────

struct Row {
  std::string case_name, method, parameter;
  double time_s = 0;
  double relative_error = 0;
  std::optional<double> relative_error_bound{}, relative_standard_error{};
  std::optional<int> seeds{}, precision{}, terms{};
  double value = 0;
};

Escalated<double> exact_moment(const KernelCase& c) {
  return c.v ? double_axis_moment_with_accuracy(c.region, c.w, *c.v, c.n) : axial_moment_with_accuracy(c.region, c.w, c.n);
}

TruncatedMoment truncated_moment(const KernelCase& c, double tolerance) {
  return c.v ? double_axis_moment_truncated(c.region, c.w, *c.v, c.n, tolerance)
             : axial_moment_truncated(c.region, c.w, c.n, tolerance);
}

std::vector<Row> measure_case(const KernelCase& c, const Reference& ref, const KernelSuiteSettings& s, bench::StatusLine& stage,
                              const std::string& prefix) {
  std::vector<Row> rows;
  const auto relative = [&](double x) { return std::abs(x - ref.value) / std::abs(ref.value); };

  stage.show(prefix + "exact");
  {
    Row r{c.name, "exact", ""};
    const Escalated<double> m = exact_moment(c);
    r.value = m.value;
    r.precision = m.precision;
    r.relative_error_bound = m.relative_error;
    r.relative_error = relative(r.value);
    r.time_s = bench::cpu_seconds_per_call([&](long) { return exact_moment(c).value; }, repetitions(s));
    rows.push_back(r);
  }
  for (double tolerance : s.tolerances) {
    stage.show(prefix + fmt::format("truncated, tolerance {:g}", tolerance));
    const TruncatedMoment t = truncated_moment(c, tolerance);
    Row r{c.name, "truncated", fmt::format("{:g}", tolerance)};
    r.value = t.value;
    r.relative_error = relative(t.value);
    r.relative_error_bound = t.error_bound / std::abs(ref.value);
    r.terms = t.terms;
    r.time_s = bench::cpu_seconds_per_call([&](long) { return truncated_moment(c, tolerance).value; }, repetitions(s));
    rows.push_back(r);
  }
  const MomentIntegrand f{c.w, c.n, c.v};
  using Estimator = MonteCarloEstimate (*)(const SphericalRegion&, const MomentIntegrand&, long, std::uint64_t);
  for (const auto& [method, estimator] : {std::pair<const char*, Estimator>{"mc_uniform", moment_uniform_stratified},
                                          std::pair<const char*, Estimator>{"mc_lobe", moment_lobe_importance}})
    for (long samples : s.samples) {
      stage.show(prefix + fmt::format("{} N = {}", method, samples));
      double error2 = 0, se2 = 0, mean = 0;
      for (int seed = 1; seed <= s.seeds; ++seed) {
        const MonteCarloEstimate e = estimator(c.region, f, samples, std::uint64_t(seed));
        error2 += (e.value - ref.value) * (e.value - ref.value);
        se2 += e.standard_error * e.standard_error;
        mean += e.value / s.seeds;
      }
      Row r{c.name, method, std::to_string(samples)};
      r.value = mean;
      r.relative_error = std::sqrt(error2 / s.seeds) / std::abs(ref.value);
      r.relative_standard_error = std::sqrt(se2 / s.seeds) / std::abs(ref.value);
      r.seeds = s.seeds;
      r.time_s = bench::cpu_seconds_per_call([&](long rep) { return estimator(c.region, f, samples, std::uint64_t(1000 + rep)).value; }, repetitions(s));
      rows.push_back(r);
    }
  return rows;
}

struct EdgeCostRow {
  std::string function;
  int edges, order;
  double time_s;
  int precision;
};

// A regular k-gon of radius 0.5 on the plane z = 1, seen from the origin; the axis is inside it,
// 6° off its centre, so every order is well conditioned and the cost is the recurrence's own.
SphericalRegion regular_polygon(int k) {
  std::vector<Vec3> poly;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * std::numbers::pi * i / k;
    poly.push_back({0.5 * std::cos(t), 0.5 * std::sin(t), 1});
  }
  return directions_through(poly, {0, 0, 0});
}

std::vector<EdgeCostRow> measure_edge_cost(const KernelSuiteSettings& s, bench::StatusLine& stage) {
  std::vector<EdgeCostRow> rows;
  const Vec3 w = normalized(Vec3{0.1, 0.05, 1});
  for (const char* function : {"axial_moment", "axial_moments"})
    for (int k : s.edges) {
      const SphericalRegion region = regular_polygon(k);
      for (int n : s.orders) {
        stage.show(fmt::format("bench kernels: cost per edge, {} with {} edges, n = {}", function, k, n));
        const bool all = function[std::char_traits<char>::length(function) - 1] == 's';
        const auto evaluate = [&](long) { return all ? axial_moments(region, w, n)[std::size_t(n)] : axial_moment(region, w, n); };
        const int precision = all ? axial_moments_with_accuracy(region, w, n).precision
                                  : axial_moment_with_accuracy(region, w, n).precision;
        rows.push_back({function, k, n, bench::cpu_seconds_per_call(evaluate, repetitions(s)), precision});
      }
    }
  return rows;
}

// ── Reports ─────────────────────────────────────────────────────────────────────────────────

std::string optional_number(const std::optional<double>& x) { return x ? fmt::format("{:.3e}", *x) : ""; }
std::string optional_int(const std::optional<int>& x) { return x ? std::to_string(*x) : ""; }
std::string quoted(const std::string& s) { return "\"" + s + "\""; }

void write_error_table(const std::string& path, const std::vector<KernelCase>& cases, const std::vector<Reference>& refs,
                       const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "case,method,parameter,time_per_eval_s,relative_error,relative_error_bound,relative_standard_error,seeds,"
       "precision,terms,value,reference,reference_relative_error,reference_method,edges,description\n";
  for (const Row& r : rows) {
    const auto i = std::size_t(std::find_if(cases.begin(), cases.end(), [&](const KernelCase& c) { return c.name == r.case_name; }) -
                               cases.begin());
    f << fmt::format("{},{},{},{:.4e},{:.3e},{},{},{},{},{},{:.17g},{:.17g},{:.1e},{},{},{}\n", r.case_name, r.method,
                     r.parameter, r.time_s, r.relative_error, optional_number(r.relative_error_bound),
                     optional_number(r.relative_standard_error), optional_int(r.seeds),
                     r.precision ? precision_name(*r.precision) : "", optional_int(r.terms), r.value, refs[i].value,
                     refs[i].relative_error, kReferenceName, cases[i].edges, quoted(cases[i].description));
  }
  if (!f) throw Error(path + ": cannot write");
}

void write_edge_table(const std::string& path, const std::vector<EdgeCostRow>& rows) {
  std::ofstream f(path);
  f << "function,edges,order,time_per_eval_s,ns_per_edge,ns_per_edge_per_order,precision\n";
  for (const EdgeCostRow& r : rows)
    f << fmt::format("{},{},{},{:.4e},{:.4g},{:.4g},{}\n", r.function, r.edges, r.order, r.time_s, 1e9 * r.time_s / r.edges,
                     1e9 * r.time_s / r.edges / r.order, precision_name(r.precision));
  if (!f) throw Error(path + ": cannot write");
}

struct MethodStyle {
  const char* method;
  const char* legend;
  PlotColour colour;
};

constexpr PlotMarker kCaseMarkers[] = {PlotMarker::circle, PlotMarker::square,        PlotMarker::triangle,
                                       PlotMarker::diamond, PlotMarker::triangle_down, PlotMarker::cross};

Plot error_plot(const std::vector<KernelCase>& cases, const std::vector<Row>& rows, const KernelSuiteSettings& s) {
  const MethodStyle methods[] = {{"exact", "exact closed form", {0.05f, 0.05f, 0.05f}},
                                 {"truncated", "early termination (tolerances)", {0.90f, 0.45f, 0.05f}},
                                 {"mc_uniform", "MC, stratified uniform in cap", {0.15f, 0.40f, 0.85f}},
                                 {"mc_lobe", "MC, stratified lobe importance", {0.10f, 0.62f, 0.30f}}};
  Plot plot;
  plot.title = "Moment kernels: relative error against run time";
  plot.subtitle = fmt::format("median time per evaluation on one core; error against {}; Monte Carlo: RMS over {} seeds",
                              kReferenceName, s.seeds);
  plot.x_label = "time per evaluation (s)";
  plot.y_label = "relative error";
  plot.y_floor = 1e-17;
  for (const MethodStyle& m : methods) plot.series.push_back({m.legend, {}, m.colour, PlotMarker::none, true});
  for (std::size_t i = 0; i < cases.size(); ++i)
    plot.series.push_back({cases[i].label, {}, {0.45f, 0.45f, 0.45f}, kCaseMarkers[i % std::size(kCaseMarkers)], false});
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (const MethodStyle& m : methods) {
      PlotSeries series{"", {}, m.colour, kCaseMarkers[i % std::size(kCaseMarkers)], true};
      for (const Row& r : rows)
        if (r.case_name == cases[i].name && r.method == m.method) series.points.push_back({r.time_s, r.relative_error});
      plot.series.push_back(std::move(series));
    }
  plot.notes = {
      fmt::format("Early termination (Arvo 1995, 5.4) at relative tolerances {:g} ... {:g}; Monte Carlo at N = {} ... {} "
                  "samples, stratified, 2 per cell.",
                  s.tolerances.front(), s.tolerances.back(), s.samples.front(), s.samples.back()),
      "MC uniform: directions uniform over the region's bounding cap; MC lobe: importance sampling of the (w.u)^n "
      "lobe. Cases: kernels_error_vs_time.csv.",
  };
  return plot;
}

Plot edge_cost_plot(const std::vector<EdgeCostRow>& rows, const KernelSuiteSettings& s) {
  const PlotColour colours[] = {{0.15f, 0.40f, 0.85f}, {0.90f, 0.45f, 0.05f}, {0.10f, 0.62f, 0.30f}, {0.6f, 0.2f, 0.6f}};
  Plot plot;
  plot.title = "Moment kernels: cost per polygon edge against the order n";
  plot.subtitle = "median time per evaluation / edges, one core; regular polygons with the axis inside";
  plot.x_label = "order n of the moment";
  plot.y_label = "ns per edge";
  double anchor_n = 0, anchor_y = 0;
  for (const char* function : {"axial_moment", "axial_moments"})
    for (std::size_t e = 0; e < s.edges.size(); ++e) {
      const bool all = std::string(function) == "axial_moments";
      PlotSeries series{fmt::format("{}, {} edges", all ? "axial_moments (all orders)" : "axial_moment", s.edges[e]), {},
                        colours[e % std::size(colours)], all ? PlotMarker::square : PlotMarker::circle, true};
      for (const EdgeCostRow& r : rows)
        if (r.function == function && r.edges == s.edges[e]) {
          series.points.push_back({double(r.order), 1e9 * r.time_s / r.edges});
          if (!all && e + 1 == s.edges.size() && r.order >= anchor_n) anchor_n = r.order, anchor_y = 1e9 * r.time_s / r.edges;
        }
      plot.series.push_back(std::move(series));
    }
  if (anchor_n > 0)
    plot.series.push_back({"linear in n (slope 1)",
                           {{double(s.orders.front()), anchor_y * s.orders.front() / anchor_n}, {anchor_n, anchor_y}},
                           {0.55f, 0.55f, 0.55f},
                           PlotMarker::none,
                           true});
  plot.notes = {"Growth is linear in n where the points follow the grey line; at small n a constant cost per edge "
                "(arc set-up) dominates. Table: kernels_cost_per_edge.csv."};
  // Where the kernel escalated its precision (moments.hpp), the cost per term changes with it.
  std::string precisions;
  for (int p = 0; p <= 2; ++p) {
    std::vector<int> orders;
    for (const EdgeCostRow& r : rows)
      if (r.precision == p && std::find(orders.begin(), orders.end(), r.order) == orders.end()) orders.push_back(r.order);
    if (!orders.empty())
      precisions += fmt::format("{}{} at n = {}", precisions.empty() ? "" : "; ", precision_name(p), fmt::join(orders, ", "));
  }
  plot.notes.push_back("Precision the kernel chose (a change of precision changes the cost per term): " + precisions + ".");
  return plot;
}

// ── The suite ───────────────────────────────────────────────────────────────────────────────

}  // namespace

int run_bench_kernels(const BenchOptions& opt) {
  const auto t0 = clock_type::now();
  const KernelSuiteSettings settings = settings_for(opt.quick);
  std::error_code ec;
  std::filesystem::create_directories(opt.out, ec);
  if (!std::filesystem::is_directory(opt.out)) throw Error(opt.out + ": cannot create the output directory");
  const std::filesystem::path dir(opt.out);

  const std::vector<KernelCase> cases = kernel_cases();
  std::vector<Reference> refs;
  std::vector<Row> rows;
  {
    bench::StatusLine stage(!opt.quiet && stderr_is_terminal());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      refs.push_back(reference_moment(cases[i]));
      if (!(refs.back().relative_error < 1e-18))
        throw Error(fmt::format("bench case {}: the reference itself is uncertain to {:.1e}", cases[i].name, refs.back().relative_error));
      const auto measured = measure_case(cases[i], refs.back(), settings, stage,
                                         fmt::format("bench kernels: case {}/{} {}: ", i + 1, cases.size(), cases[i].name));
      rows.insert(rows.end(), measured.begin(), measured.end());
    }
    const std::vector<EdgeCostRow> edge_rows = measure_edge_cost(settings, stage);
    stage.show("bench kernels: writing tables and plots");

    StagedOutputs outputs;
    const std::string error_csv = (dir / "kernels_error_vs_time.csv").string(), error_png = (dir / "kernels_error_vs_time.png").string();
    const std::string edge_csv = (dir / "kernels_cost_per_edge.csv").string(), edge_png = (dir / "kernels_cost_per_edge.png").string();
    write_error_table(outputs.stage(error_csv), cases, refs, rows);
    write_edge_table(outputs.stage(edge_csv), edge_rows);
    write_loglog_plot(outputs.stage(error_png), error_plot(cases, rows, settings));
    write_loglog_plot(outputs.stage(edge_png), edge_cost_plot(edge_rows, settings));
    outputs.commit();
    if (!opt.quiet) stage.show(fmt::format("bench kernels: done in {:.1f} s", seconds_since(t0)));
    if (!opt.quiet && !stderr_is_terminal())
      std::cerr << fmt::format("bench kernels: wrote {}, {}, {}, {} ({:.1f} s)\n", error_csv, error_png, edge_csv, edge_png,
                               seconds_since(t0));
  }
  return 0;
}

}  // namespace daylit::cli
