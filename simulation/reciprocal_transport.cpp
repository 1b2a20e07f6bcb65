#include "simulation/reciprocal_transport.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace daylit {

namespace {

constexpr std::uint32_t kNone = std::uint32_t(-1);

template <class F>
void for_rows(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t u = r.begin(); u != r.end(); ++u) f(u);
  });
}

// In index order, so that the result does not depend on the threads.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

void sort_row(TransportRow& row) {
  std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
}

// Per live row j, the live rows u that have column j and where in row u it is, in increasing u
// (a transpose by buckets: linear in the entries).
struct Transpose {
  std::vector<std::size_t> begin;                            // per row, n + 1
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at;   // (u, position of j in row u)
};
template <class Live>
Transpose transpose(const std::vector<TransportRow>& rows, const Live& live) {
  const std::size_t n = rows.size();
  Transpose t;
  t.begin.assign(n + 1, 0);
  for (std::size_t u = 0; u < n; ++u)
    if (live(u))
      for (const auto& e : rows[u])
        if (live(e.first)) ++t.begin[e.first + 1];
  for (std::size_t j = 0; j < n; ++j) t.begin[j + 1] += t.begin[j];
  t.at.resize(t.begin[n]);
  std::vector<std::size_t> fill(t.begin.begin(), t.begin.end() - 1);
  for (std::size_t u = 0; u < n; ++u)
    if (live(u))
      for (std::size_t i = 0; i < rows[u].size(); ++i)
        if (live(rows[u][i].first)) t.at[fill[rows[u][i].first]++] = {std::uint32_t(u), std::uint32_t(i)};
  return t;
}

}  // namespace

ReciprocityReport make_reciprocal(std::vector<TransportRow>& rows, const std::vector<double>& weight) {
  const std::size_t n = rows.size();
  ReciprocityReport report;
  const auto live = [&](std::size_t u) { return weight[u] > 0; };

  // Columns sorted, duplicates (an element seen twice, e.g. inside and through a pane) merged.
  for_rows(n, [&](std::size_t u) {
    TransportRow& row = rows[u];
    sort_row(row);
    std::size_t k = 0;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (k > 0 && row[k - 1].first == row[i].first)
        row[k - 1].second += row[i].second;
      else
        row[k++] = row[i];
    }
    row.resize(k);
  });

  // The partner (j, u) of every collocated (u, j) between live unknowns, added with K = 0 where
  // node j sees nothing of u's element while node u sees part of j's (one-sided visibility):
  // row j and the transpose's bucket j, both sorted, merged.
  Transpose tr = transpose(rows, live);
  std::vector<std::vector<std::uint32_t>> missing(n);
  for_rows(n, [&](std::size_t j) {
    if (!live(j)) return;
    const TransportRow& row = rows[j];
    std::size_t i = 0;
    for (std::size_t b = tr.begin[j]; b < tr.begin[j + 1]; ++b) {
      const std::uint32_t u = tr.at[b].first;
      while (i < row.size() && row[i].first < u) ++i;
      if (i == row.size() || row[i].first != u) missing[j].push_back(u);
    }
  });
  for (std::size_t j = 0; j < n; ++j) {
    if (missing[j].empty()) continue;
    report.entries_added += missing[j].size();
    for (std::uint32_t u : missing[j]) rows[j].emplace_back(u, 0.0);
    sort_row(rows[j]);
  }
  missing.clear();
  if (report.entries_added > 0) tr = transpose(rows, live);

  // Where each entry's partner is: every live (u, j) now has its (j, u).
  std::vector<std::vector<std::uint32_t>> partner(n);
  for_rows(n, [&](std::size_t j) {
    if (!live(j)) return;
    const TransportRow& row = rows[j];
    partner[j].assign(row.size(), kNone);
    std::size_t i = 0;
    for (std::size_t b = tr.begin[j]; b < tr.begin[j + 1]; ++b) {
      const auto [u, at] = tr.at[b];
      while (row[i].first < u) ++i;
      partner[j][i] = at;
    }
  });
  tr = {};

  // S = (G + Gᵀ)/2 on live pairs (0 towards sides left out), what escapes X, and d.
  std::vector<std::vector<double>> s(n);
  std::vector<double> escape(n, 0.0), diagonal(n, 0.0), d(n, 0.0), row_sum(n, 0.0);
  for_rows(n, [&](std::size_t u) {
    if (!live(u)) return;
    s[u].assign(rows[u].size(), 0.0);
    double received = 0, degree = 0, defect = 0, f = 0;
    for (std::size_t i = 0; i < rows[u].size(); ++i) {
      const auto [j, k] = rows[u][i];
      const double g = weight[u] * k;
      received += g;
      f += k;
      if (partner[u][i] == kNone) continue;
      s[u][i] = (g + weight[j] * rows[j][partner[u][i]].second) / 2;  // the same from both sides
      degree += std::abs(s[u][i]);
      defect += s[u][i] - g;
    }
    row_sum[u] = f;
    escape[u] = weight[u] - received;
    diagonal[u] = degree + std::abs(escape[u]);
    d[u] = defect;
  });
  for (std::size_t u = 0; u < n; ++u) {
    if (!live(u)) continue;
    ++report.unknowns;
    report.entries += s[u].size();
    report.reciprocity_defect = std::max(report.reciprocity_defect, std::abs(d[u]) / weight[u]);
  }
  partner = {};

  // (diag + |S|) λ = d by conjugate gradients, Jacobi-preconditioned.
  const auto apply = [&](const std::vector<double>& x, std::vector<double>& y) {
    for_rows(n, [&](std::size_t u) {
      if (!live(u)) return;
      double v = diagonal[u] * x[u];
      for (std::size_t i = 0; i < rows[u].size(); ++i) v += std::abs(s[u][i]) * x[rows[u][i].first];
      y[u] = v;
    });
  };
  const auto precondition = [&](const std::vector<double>& r, std::vector<double>& z) {
    for (std::size_t u = 0; u < n; ++u) z[u] = diagonal[u] > 0 ? r[u] / diagonal[u] : 0;
  };
  // The closure defect left, relative to the node's weight: 1e-15 is the roundoff of the rows'
  // own sums (the closed box's rows sum to 1 within it).
  const auto worst = [&](const std::vector<double>& r) {
    double m = 0;
    for (std::size_t u = 0; u < n; ++u)
      if (live(u)) m = std::max(m, std::abs(r[u]) / weight[u]);
    return m;
  };
  std::vector<double> lambda(n, 0.0), r = d, z(n, 0.0), p(n, 0.0), q(n, 0.0);
  precondition(r, z);
  p = z;
  double rz = dot(r, z);
  constexpr int kMaxIterations = 2000;
  while (worst(r) > 1e-15 && report.iterations < kMaxIterations && rz > 0) {
    ++report.iterations;
    apply(p, q);
    const double pq = dot(p, q);
    if (!(pq > 0)) break;
    const double alpha = rz / pq;
    for (std::size_t u = 0; u < n; ++u) {
      lambda[u] += alpha * p[u];
      r[u] -= alpha * q[u];
    }
    precondition(r, z);
    const double rz_next = dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t u = 0; u < n; ++u) p[u] = z[u] + beta * p[u];
  }

  // K' = G'/w in place, and what the change did (G_ju = 2 S_uj − G_uj, to rounding).
  std::vector<double> entry_change(n, 0.0), closure(n, 0.0);
  for_rows(n, [&](std::size_t u) {
    if (!live(u)) return;
    double total = 0, f = 0;
    for (std::size_t i = 0; i < rows[u].size(); ++i) {
      auto& [j, k] = rows[u][i];
      const double g = weight[u] * k;
      if (live(j)) {
        const double g_new = s[u][i] - std::abs(s[u][i]) * (lambda[u] + lambda[j]);
        entry_change[u] = std::max(entry_change[u], std::abs(g_new - g) / std::max(std::abs(g), std::abs(2 * s[u][i] - g)));
        k = g_new / weight[u];
        total += g_new;
      } else {
        total += g;
      }
      f += k;
    }
    closure[u] = total + (escape[u] - std::abs(escape[u]) * lambda[u]) - weight[u];
    row_sum[u] = std::abs(f - row_sum[u]);  // now the change of the row's sum
  });
  for (std::size_t u = 0; u < n; ++u) {
    report.max_entry_change = std::max(report.max_entry_change, entry_change[u]);
    if (live(u)) report.max_row_change = std::max(report.max_row_change, row_sum[u]);
  }
  report.residual = worst(closure);
  return report;
}

}  // namespace daylit
