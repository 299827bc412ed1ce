/// \file distributions.h
/// \brief Upper tails of the distributions mpcal's tests use (χ² for the
/// repeatability and split-half checks, F for the bias-drift test), in
/// closed form or by the continued fraction of the incomplete beta function:
/// no dependency beyond <cmath>.
#pragma once

namespace mpcal {

/// Upper-tail probability of the chi-square distribution,
/// P(χ²_dof ≥ chi2), for dof ≥ 1 (closed form for integer dof).
/// \pre dof >= 1, chi2 >= 0.
double ChiSquareUpperTail(double chi2, int dof);

/// P(F ≥ f) for the F distribution with (d1, d2) degrees of freedom: the
/// regularised incomplete beta I_x(d2/2, d1/2), x = d2/(d2 + d1 f); 1 for
/// f <= 0.
double FUpperTail(double f, int d1, int d2);

}  // namespace mpcal
