#pragma once
// Reciprocity and closure for the collocated transport, so that the discrete radiosity system
// conserves energy exactly (DESIGN.md §4, "Audit").
//
// Collocation gives, per unknown u (a node of an element side), a row K_uj: the irradiance at the
// node per unit value of unknown j's basis function. With w_u = A/3 the node's weight in the
// degree-2 area rule (∫φ_u dA = A/3), G_uj = w_u K_uj is the flux that u's share of its element
// receives from j. The Galerkin exchange ∫∫ φ_u k φ_j is symmetric in u and j; G only to the
// order of the mesh (the receiver's integral is taken at one point), and an asymmetric G does not
// conserve energy: with M = ρ(E₀ + KM) solved exactly, first-bounce flux − absorbed − escaping
// = Σ_uj G_uj (M_u − M_j), which vanishes for every M only if G is symmetric (measured on the
// 4 × 5 × 3 m room: −2.7e-4 of the first-bounce flux at the default mesh).
//
// So the transport is replaced by the symmetric G' nearest to G, in the manner of the
// least-squares smoothing of exchange areas that zonal methods use to enforce reciprocity and
// closure (Larsen and Howell 1986, "Least-squares smoothing of direct-exchange areas in zonal
// analysis", J. Heat Transfer 108, 239–242), here with these choices:
//   - every node's emission is accounted for exactly (closure): Σ_j G'_uj + X'_u = w_u, where
//     X_u = w_u (1 − Σ_j K_uj) is what leaves u unreceived (through apertures, to the far ground,
//     to sides left out) and X'_u its adjusted value;
//   - minimise Σ_pairs (G'_uj − S_uj)²/|S_uj| + Σ_u (X'_u − X_u)²/|X_u|, S = (G + Gᵀ)/2: each
//     change is relative to the size of what it changes, an exchange that is zero stays zero, and
//     a node that sees nothing outside (X_u = 0: the inside of a closed box) keeps its row sum
//     exactly, so a closed enclosure's rows still sum to 1 and its uniform solution is unchanged.
// The Lagrange conditions give G'_uj = S_uj − |S_uj| (λ_u + λ_j), X'_u = X_u − |X_u| λ_u, with
//     (diag(Σ_j |S_uj| + |X_u|) + |S|) λ = d,   d_u = Σ_j (S_uj − G_uj),
// a symmetric positive semi-definite system (a signless graph Laplacian plus |X|, definite where
// every part of the visibility graph that is bipartite has some escape), solved by conjugate
// gradients preconditioned by Jacobi and a coarse correction (below). G' is symmetric to the last bit (λ_u + λ_j is computed
// the same from both sides), so energy is conserved to roundoff on every mesh whatever the
// solver's residual, which only sets how closely the row sums keep their collocated values.
//
// The coarse correction. Two surfaces that face each other closely and see little else (a
// ground polygon 1 cm below a building's floor: each node of the floor's underside sees the
// ground element just below it, that element's nodes see the floor above it, and almost nothing
// escapes) make small, nearly closed, nearly bipartite parts of the graph, each with a near-null
// vector of the system: λ = +c on one side's nodes, −c on the other's. Jacobi leaves them to
// hundreds of iterations (473 on an L-shaped house with a ground polygon 1 cm below its floor, 29
// without that ground). Such a vector is local and signed, not smooth (a lattice of groups per
// surface side, tried first, changed nothing), so the coarse space is algebraic: nodes joined
// by strong exchanges (|S_uj| at least a fifth of the smaller diagonal) are aggregated around a
// root, each with the sign opposite to its root's (smoothed-aggregation multigrid's plain
// aggregation, with the sign of a signless Laplacian's near-null vectors), and the
// preconditioner is D⁻¹ + Z (Zᵀ A Z)⁻¹ Zᵀ (two-level additive Schwarz), Z the aggregates' signed
// indicators. Rooms whose nodes each see many others have no strong exchanges and no coarse
// space: Jacobi alone, as before. Over 2,000 aggregates the coarse space is left out (its dense
// Cholesky would cost more than it saves).
// The changes are of the order of the collocation's own reciprocity defect (O(h²) for linear
// elements); the report gives their size.

#include <cstddef>
#include <vector>

#include "simulation/radiosity_solver.hpp"

namespace daylit {

struct ReciprocityReport {
  std::size_t unknowns = 0;          // with weight > 0
  std::size_t entries = 0;           // between such unknowns, after adding missing partners
  std::size_t entries_added = 0;     // (j, u) where only (u, j) was collocated (one-sided visibility)
  double reciprocity_defect = 0;     // max_u |d_u| / w_u: the collocation's own asymmetry
  double max_entry_change = 0;       // max |G'_uj − G_uj| / max(|G_uj|, |G_ju|)
  double max_row_change = 0;         // max_u |Σ_j K'_uj − Σ_j K_uj|: the escaping fraction's change
  int iterations = 0;                // of conjugate gradients
  std::size_t coarse_aggregates = 0;  // of the coarse correction (0: Jacobi alone)
  double residual = 0;               // max_u |closure defect| / w_u after them
};

// Replaces `rows` (K, rows of unknowns of weight `weight[u]`, model units²) by the reciprocal and
// closed K' above. Unknowns of weight 0 (sides left out) take no part: their rows stay as they are
// and entries towards them count as escaping. Rows' entries are sorted by column and duplicate
// columns merged. Cost: O(entries · log(row length)) for the sort, O(entries) for the pairing (a
// sweep, in parallel), then O(entries) per iteration (about 20–60 on rooms).
// `collocated`, where given, receives K as it was, row by row in the order of the entries of
// `rows` as returned (sorted and merged, partners added with 0): a refinement that reuses rows
// needs the collocated values, and this is 8 bytes an entry where a copy of K is 16.
ReciprocityReport make_reciprocal(std::vector<TransportRow>& rows, const std::vector<double>& weight,
                                  std::vector<std::vector<double>>* collocated = nullptr);

}  // namespace daylit
