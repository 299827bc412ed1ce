// Private to src/noise/: what the term fit (noise_fit.cc AnalyseAxis) reports
// of the IEEE terms, for it and for extra_terms.cc: the terms measured with
// their intervals, the bounds and record-length advice for those not, and
// the fitted model checked against the curve.
#pragma once

#include <vector>

#include "mpcal/noise.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {

/// A coefficient's value and interval from its variance, as a scaled χ² with
/// ν = 2 c² / var(c) degrees of freedom (exact for one point; keeps the
/// interval positive): √c and the limits of √c.
struct RootInterval {
  double value = 0.0;
  double lo = 0.0;
  double hi = 0.0;
};

RootInterval CoefficientInterval(double c, double variance, double confidence);

/// Measured terms: value and interval from the coefficient's variance.
void MeasureTerms(const std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  const NoiseOptions& o,
                  AxisNoise& out);

/// The terms not measured: the tightest upper confidence limit of the term
/// alone, and for bias instability and random walk whether a longer record
/// would show them at that bound and how long (RecordNeeded).
void BoundTerms(const std::vector<AllanPoint>& curve,
                const Fit& fit,
                double record_s,
                const NoiseOptions& o,
                AxisNoise& out);

/// The fitted model `m` against the curve: the cluster times where its σ(τ)
/// lies outside the curve's interval, and their runs.
ModelCheck CheckModel(const std::vector<AllanPoint>& curve,
                      const Model& m,
                      const NoiseOptions& o);

}  // namespace mpcal::internal::noise_fit
