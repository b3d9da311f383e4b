#pragma once
// A CHOLMOD factor of K_bar with the rail DOFs ordered last, and the
// triangular solves restricted to its trailing columns (the suffix).
//
// With P K_bar P^T = L D L^T and the rail DOFs in the suffix S:
//  - a right-hand side that is zero outside the rail DOFs has a forward
//    image (L D)^-1 P b that is zero before S, and its part in S needs only
//    L's columns in S;
//  - the rows S of x = P^T L^-T y need only y's part in S and L's columns
//    in S (back-substitution runs from the last column).
// So a condensed step (free prediction, contact problem at the rail DOFs,
// back-substitution of the contact forces) costs one forward and one
// backward pass over the whole factor, one solve, instead of two solves,
// plus two passes over the suffix (README "One solve per step").
#include <cholmod.h>

#include <vector>

#include "core/types.hpp"

namespace railvsi {

// The analysis of `A` (its upper triangle) with the DOFs `last` ordered
// after all others, the rest in the order of CHOLMOD's own fill-reducing
// choice, when that costs at most `max_fill_growth` times the nonzeros of
// CHOLMOD's own analysis; null otherwise (the caller keeps `own`). The etree
// is not postordered: a postorder could move columns of `last` before
// others.
cholmod_factor* analyze_with_last(cholmod_sparse* A, const cholmod_factor& own, double own_nonzeros,
                                  const std::vector<int>& last, double max_fill_growth, cholmod_common* c);

// The first column (in the factor's order) of the suffix that holds the
// DOFs `last` (all in L's trailing positions, as analyze_with_last gives),
// moved back to the first column of its supernode; -1 if some DOF of
// `last` is not in the trailing positions.
int suffix_start(const cholmod_factor& L, const std::vector<int>& last);

// In place on the suffix [start, n) of the factor's order, z[k - start]:
//   forward:  z := (L D)^-1 z  (L D = L for an LL' factor);
//   backward: z := L^-T z.
// Exact for a right-hand side that is zero before `start` (forward), and for
// the rows in the suffix (backward).
void suffix_forward(const cholmod_factor& L, int start, double* z);
void suffix_backward(const cholmod_factor& L, int start, double* z);

// K_bar^-1 restricted to the suffix, in the factor's order: the inverse of
// the suffix's own block of L D L^T (the Cholesky factor of the Schur
// complement of the rest), by LAPACK's dpotri on that block made dense.
// Sized (n - start)^2: for a suffix of a few thousand columns.
DenseMatrix suffix_inverse(const cholmod_factor& L, int start);

}  // namespace railvsi
