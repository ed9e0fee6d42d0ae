#pragma once
// Quantiles of the normal and chi-square distributions, for the evidence tests of the estimators
// (a change, a move, a spread against what noise gives). The chi-square quantile is
// Wilson-Hilferty's approximation (the cube of a normal quantile): high by 1.8 % at 3 degrees
// and tail 0.001, by 0.6 % at 10, less with more degrees or a wider tail.

namespace irloc {

// The z with P(N(0,1) > z) = tail, for tail in (0, 0.5]; by bisection of erfc, to double precision
// (a search: for start-up, not per frame).
double normal_upper_quantile(double tail);

// The chi-square value that `degrees` (>= 1) degrees of freedom exceed with probability `tail`.
double chi_square_quantile(int degrees, double tail);

// The same from the normal quantile of the tail (normal_upper_quantile(tail)): no search, for a
// caller that asks for many degrees at one tail (per frame).
double chi_square_quantile_at(int degrees, double normal_quantile);

}  // namespace irloc
