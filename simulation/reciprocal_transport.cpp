#include "simulation/reciprocal_transport.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Core>
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

// A mesh's rows arrive sorted (they list the elements in order), a refinement's kept rows in two
// sorted runs (the new elements' entries follow the old ones'): a check costs a read and a merge
// of two runs a pass, where a sort costs n log n comparisons.
void sort_row(TransportRow& row) {
  const auto by_column = [](const auto& a, const auto& b) { return a.first < b.first; };
  const auto run = std::is_sorted_until(row.begin(), row.end(), by_column);
  if (run == row.end()) return;
  if (std::is_sorted(run, row.end(), by_column))
    std::inplace_merge(row.begin(), run, row.end(), by_column);
  else
    std::sort(row.begin(), row.end(), by_column);
}

// The sweep below runs in this many chunks of rows (each keeps a cursor per row).
std::size_t partner_chunks(std::size_t n) { return std::min<std::size_t>(n, 16); }

// Calls visit(chunk, u, partner) for every live row u, with partner[i] the position of column u in
// row j = rows[u][i].first where j is live and row j holds it, kNone otherwise. The rows, sorted
// by column, are swept in chunks of increasing u in parallel; a chunk's cursor in row j starts at
// j's first column at or after the chunk's first row and only moves forward, so each chunk reads
// the rows in order: linear in the entries, and nothing as large as K allocated (a transpose of
// the office's 14 million entries cost more in page faults than in work).
template <class Live, class Visit>
void sweep_partners(const std::vector<TransportRow>& rows, const Live& live, Visit&& visit) {
  const std::size_t n = rows.size(), chunks = partner_chunks(n);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t begin = c * n / chunks, end = (c + 1) * n / chunks;
    std::vector<std::size_t> cursor(n);
    for (std::size_t j = 0; j < n; ++j)
      cursor[j] = std::size_t(std::lower_bound(rows[j].begin(), rows[j].end(), begin,
                                               [](const auto& e, std::size_t u) { return e.first < u; }) -
                              rows[j].begin());
    std::vector<std::uint32_t> partner;
    for (std::size_t u = begin; u < end; ++u) {
      if (!live(u)) continue;
      partner.assign(rows[u].size(), kNone);
      for (std::size_t i = 0; i < rows[u].size(); ++i) {
        const std::uint32_t j = rows[u][i].first;
        if (!live(j)) continue;
        const TransportRow& other = rows[j];
        std::size_t& at = cursor[j];
        while (at < other.size() && other[at].first < u) ++at;
        if (at < other.size() && other[at].first == u) partner[i] = std::uint32_t(at);
      }
      visit(c, u, partner);
    }
  });
}

// The coarse space of the preconditioner (header): per unknown its aggregate (kNone: none) and
// sign, and the Cholesky factor of Zᵀ A Z.
struct CoarseSpace {
  std::vector<std::uint32_t> aggregate;
  std::vector<double> sign;
  std::vector<std::vector<std::uint32_t>> members;
  Eigen::LLT<Eigen::MatrixXd> factor;
  bool usable() const { return !members.empty(); }
};

constexpr double kStrongExchange = 0.2;     // |S_uj| ≥ this × min(diagonal_u, diagonal_j)
constexpr std::size_t kMaxAggregates = 2000;  // the dense Cholesky: 2.7e9 operations, 32 MB

// A = diag(diagonal) + |S| (rows `s`, columns `column`). Plain aggregation in index order, so
// that the same system gives the same aggregates: a root all of whose strong neighbours are
// free takes them (sign −1 against its +1); then a free node with a strong neighbour joins the
// strongest one's aggregate with the sign opposite to it.
CoarseSpace coarse_space(const std::vector<double>& diagonal, const std::vector<std::vector<double>>& s,
                         const std::vector<std::vector<std::uint32_t>>& column) {
  const std::size_t n = diagonal.size();
  CoarseSpace c;
  c.aggregate.assign(n, kNone);
  c.sign.assign(n, 0.0);
  const auto strong = [&](std::size_t u, std::size_t i) {
    const std::uint32_t j = column[u][i];
    return diagonal[u] > 0 && diagonal[j] > 0 && std::abs(s[u][i]) >= kStrongExchange * std::min(diagonal[u], diagonal[j]);
  };
  std::size_t count = 0;
  for (std::size_t u = 0; u < n; ++u) {
    bool any = false, free = true;
    for (std::size_t i = 0; i < s[u].size() && free; ++i)
      if (strong(u, i)) {
        any = true;
        free = c.aggregate[column[u][i]] == kNone && column[u][i] != u;
      }
    if (!any || !free || c.aggregate[u] != kNone) continue;
    c.aggregate[u] = std::uint32_t(count);
    c.sign[u] = 1;
    for (std::size_t i = 0; i < s[u].size(); ++i)
      if (strong(u, i)) {
        c.aggregate[column[u][i]] = std::uint32_t(count);
        c.sign[column[u][i]] = -1;
      }
    ++count;
  }
  for (std::size_t u = 0; u < n; ++u) {
    if (c.aggregate[u] != kNone) continue;
    double best = 0;
    std::uint32_t to = kNone;
    for (std::size_t i = 0; i < s[u].size(); ++i) {
      const std::uint32_t j = column[u][i];
      if (strong(u, i) && c.aggregate[j] != kNone && std::abs(s[u][i]) > best) {
        best = std::abs(s[u][i]);
        to = j;
      }
    }
    if (to == kNone) continue;
    c.aggregate[u] = c.aggregate[to];
    c.sign[u] = -c.sign[to];
  }
  if (count == 0 || count > kMaxAggregates) return CoarseSpace{};
  c.members.resize(count);
  for (std::size_t u = 0; u < n; ++u)
    if (c.aggregate[u] != kNone) c.members[c.aggregate[u]].push_back(std::uint32_t(u));
  // Row a of Zᵀ A Z by one task: over a's members, their diagonal and their signed |S| towards
  // each aggregate.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(Eigen::Index(count), Eigen::Index(count));
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t g) {
    for (const std::uint32_t u : c.members[g]) {
      a(Eigen::Index(g), Eigen::Index(g)) += diagonal[u];
      for (std::size_t i = 0; i < s[u].size(); ++i) {
        const std::uint32_t j = column[u][i];
        if (c.aggregate[j] != kNone)
          a(Eigen::Index(g), Eigen::Index(c.aggregate[j])) += c.sign[u] * c.sign[j] * std::abs(s[u][i]);
      }
    }
  });
  c.factor.compute(a);  // reads the lower triangle
  if (c.factor.info() != Eigen::Success) return CoarseSpace{};
  return c;
}

}  // namespace

ReciprocityReport make_reciprocal(std::vector<TransportRow>& rows, const std::vector<double>& weight,
                                  std::vector<std::vector<double>>* collocated) {
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

  // S = (G + Gᵀ)/2 on live pairs (0 towards sides left out), what escapes X, and d, row u from
  // the positions of its entries' partners (j, u) in the rows j.
  // The columns again, apart from K's values: conjugate gradients read only them and S, 12 bytes
  // an entry instead of 24 (it is bound by memory traffic).
  std::vector<std::vector<double>> s(n);
  std::vector<std::vector<std::uint32_t>> column(n);
  std::vector<double> escape(n, 0.0), diagonal(n, 0.0), d(n, 0.0), row_sum(n, 0.0);
  const auto fill = [&](std::size_t u, const std::vector<std::uint32_t>& partner) {
    s[u].assign(rows[u].size(), 0.0);
    column[u].resize(rows[u].size());
    for (std::size_t i = 0; i < rows[u].size(); ++i) column[u][i] = rows[u][i].first;
    double received = 0, degree = 0, defect = 0, f = 0;
    for (std::size_t i = 0; i < rows[u].size(); ++i) {
      const auto [j, k] = rows[u][i];
      const double g = weight[u] * k;
      received += g;
      f += k;
      if (partner[i] == kNone) continue;
      s[u][i] = (g + weight[j] * rows[j][partner[i]].second) / 2;  // the same from both sides
      degree += std::abs(s[u][i]);
      defect += s[u][i] - g;
    }
    row_sum[u] = f;
    escape[u] = weight[u] - received;
    diagonal[u] = degree + std::abs(escape[u]);
    d[u] = defect;
  };

  // The partner (j, u) of every collocated (u, j) between live unknowns, added with K = 0 where
  // node j sees nothing of u's element while node u sees part of j's (one-sided visibility).
  // missing[j] lists such u in increasing u: the chunks' finds, in the chunks' order. Where none
  // is missing (every pair seen from both ends, as in most rooms) the same sweep fills S; else
  // the rows grow by the missing partners and a second sweep fills it.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(partner_chunks(n));
  sweep_partners(rows, live, [&](std::size_t chunk, std::size_t u, const std::vector<std::uint32_t>& partner) {
    for (std::size_t i = 0; i < partner.size(); ++i)
      if (partner[i] == kNone && live(rows[u][i].first)) found[chunk].emplace_back(std::uint32_t(rows[u][i].first), std::uint32_t(u));
    fill(u, partner);
  });
  std::vector<std::vector<std::uint32_t>> missing(n);
  for (const auto& list : found)
    for (const auto& [j, u] : list) missing[j].push_back(u);
  found = {};
  // Both lists are sorted by column and share none: merged, row j is sorted as a sort would leave it.
  for_rows(n, [&](std::size_t j) {
    if (missing[j].empty()) return;
    TransportRow merged;
    merged.reserve(rows[j].size() + missing[j].size());
    auto it = rows[j].begin();
    for (std::uint32_t u : missing[j]) {
      for (; it != rows[j].end() && it->first < u; ++it) merged.push_back(*it);
      merged.emplace_back(u, 0.0);
    }
    merged.insert(merged.end(), it, rows[j].end());
    rows[j] = std::move(merged);
  });
  for (std::size_t j = 0; j < n; ++j) report.entries_added += missing[j].size();
  missing = {};
  // Every live (u, j) now has its (j, u).
  if (report.entries_added > 0)
    sweep_partners(rows, live, [&](std::size_t, std::size_t u, const std::vector<std::uint32_t>& partner) { fill(u, partner); });
  for (std::size_t u = 0; u < n; ++u) {
    if (!live(u)) continue;
    ++report.unknowns;
    report.entries += s[u].size();
    report.reciprocity_defect = std::max(report.reciprocity_defect, std::abs(d[u]) / weight[u]);
  }

  // (diag + |S|) λ = d by conjugate gradients, Jacobi-preconditioned. |S| is symmetric to the last
  // bit (S_uj is computed the same from both ends) and the rows are sorted, so the product reads
  // each row from its diagonal on (columns ≥ u) and adds each entry to both ends: half the memory
  // traffic of the whole rows, which bounds this loop. In a fixed number of chunks of about equal
  // entries, each into its own vector, summed in chunk order: the same sums whatever the threads.
  std::vector<std::size_t> upper(n, 0);
  for_rows(n, [&](std::size_t u) {
    upper[u] = std::size_t(std::lower_bound(column[u].begin(), column[u].end(), std::uint32_t(u)) - column[u].begin());
  });
  constexpr std::size_t kProductChunks = 8;
  std::vector<std::size_t> chunk_start(kProductChunks + 1, n);
  {
    std::size_t total = 0;
    for (std::size_t u = 0; u < n; ++u)
      if (live(u)) total += column[u].size() - upper[u];
    std::size_t seen = 0, c = 0;
    for (std::size_t u = 0; u < n; ++u) {
      while (c < kProductChunks && seen >= c * total / kProductChunks) chunk_start[c++] = u;
      if (live(u)) seen += column[u].size() - upper[u];
    }
  }
  std::vector<std::vector<double>> partial(kProductChunks, std::vector<double>(n, 0.0));
  const auto apply = [&](const std::vector<double>& x, std::vector<double>& y) {
    tbb::parallel_for(std::size_t(0), kProductChunks, [&](std::size_t c) {
      std::vector<double>& part = partial[c];
      std::fill(part.begin(), part.end(), 0.0);
      for (std::size_t u = chunk_start[c]; u < chunk_start[c + 1]; ++u) {
        if (!live(u)) continue;
        const std::uint32_t* j = column[u].data();
        const double* su = s[u].data();
        const double xu = x[u];
        double v = 0;
        std::size_t i = upper[u];
        if (i < column[u].size() && j[i] == u) v += std::abs(su[i++]) * xu;  // an exchange with itself, once
        for (; i < column[u].size(); ++i) {
          const double a = std::abs(su[i]);
          v += a * x[j[i]];
          part[j[i]] += a * xu;
        }
        part[u] += v;
      }
    });
    for (std::size_t u = 0; u < n; ++u) {
      if (!live(u)) continue;
      double v = diagonal[u] * x[u];
      for (std::size_t c = 0; c < kProductChunks; ++c) v += partial[c][u];
      y[u] = v;
    }
  };
  const CoarseSpace coarse = coarse_space(diagonal, s, column);
  report.coarse_aggregates = coarse.members.size();
  const auto precondition = [&](const std::vector<double>& r, std::vector<double>& z) {
    for (std::size_t u = 0; u < n; ++u) z[u] = diagonal[u] > 0 ? r[u] / diagonal[u] : 0;
    if (!coarse.usable()) return;
    Eigen::VectorXd rc(Eigen::Index(coarse.members.size()));
    for (std::size_t g = 0; g < coarse.members.size(); ++g) {
      double sum = 0;
      for (const std::uint32_t u : coarse.members[g]) sum += coarse.sign[u] * r[u];
      rc(Eigen::Index(g)) = sum;
    }
    const Eigen::VectorXd y = coarse.factor.solve(rc);
    for (std::size_t u = 0; u < n; ++u)
      if (coarse.aggregate[u] != kNone) z[u] += coarse.sign[u] * y(Eigen::Index(coarse.aggregate[u]));
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

  // K' = G'/w in place, and what the change did (G_ju = 2 S_uj − G_uj, to rounding). With
  // `collocated`, s[u] takes K's values as it goes (S_uj is read once, just before).
  std::vector<double> entry_change(n, 0.0), closure(n, 0.0);
  const bool keep = collocated != nullptr;
  for_rows(n, [&](std::size_t u) {
    if (!live(u)) {
      if (keep) {
        s[u].resize(rows[u].size());
        for (std::size_t i = 0; i < rows[u].size(); ++i) s[u][i] = rows[u][i].second;
      }
      return;
    }
    double total = 0, f = 0;
    for (std::size_t i = 0; i < rows[u].size(); ++i) {
      auto& [j, k] = rows[u][i];
      const double g = weight[u] * k;
      const double s_uj = s[u][i];
      if (keep) s[u][i] = k;
      if (live(j)) {
        const double g_new = s_uj - std::abs(s_uj) * (lambda[u] + lambda[j]);
        entry_change[u] = std::max(entry_change[u], std::abs(g_new - g) / std::max(std::abs(g), std::abs(2 * s_uj - g)));
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
  if (keep) *collocated = std::move(s);
  return report;
}

}  // namespace daylit
