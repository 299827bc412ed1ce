// Convergence Monte Carlo: from the automatic six-position
// initialisation, every simulated session with consumer-grade errors (bias
// 0.5 g, scale error 10 %, non-orthogonality 0.05 rad) converges to the
// truth: within 6 bound-σ on every parameter.
//
//   mpcal_convergence_bench [SESSIONS=1000] [SEED=1]
#include <cstdlib>

#include <fmt/format.h>

#include "monte_carlo.h"

int main(int argc, char** argv) {
  using namespace mpcal;
  const int sessions = argc > 1 ? std::atoi(argv[1]) : 1000;
  std::mt19937_64 rng(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1);
  bench::Envelope envelope;
  envelope.max_bias_g = 0.5;
  envelope.max_scale_error = 0.10;
  envelope.max_angle_rad = 0.05;
  envelope.min_positions = 18;
  envelope.max_positions = 30;
  // Six bound-σ: a Gaussian error goes beyond it once in 5e8 draws, so any
  // hit is a wrong solution, not noise.
  constexpr double kConvergedWithinBoundSigma = 6.0;

  int not_converged = 0, wrong = 0;
  for (int i = 0; i < sessions; ++i) {
    const auto options = bench::DrawSession(envelope, rng);
    const auto outcome = bench::RunSession(options);
    if (!outcome) {
      ++not_converged;
      fmt::print("session {} (seed {}): no convergence\n", i, options.seed);
    } else if (outcome->error_over_bound.cwiseAbs().maxCoeff() >
               kConvergedWithinBoundSigma) {
      ++wrong;
      fmt::print("session {} (seed {}): converged {:.1f} bound-σ from the truth\n",
                 i,
                 options.seed,
                 outcome->error_over_bound.cwiseAbs().maxCoeff());
    }
  }
  fmt::print(
      "convergence: {} sessions (bias <= {} g, scale error <= {}, angles <= {} rad, "
      "{}-{} positions): {} did not converge, {} converged elsewhere; {}\n",
      sessions,
      envelope.max_bias_g,
      envelope.max_scale_error,
      envelope.max_angle_rad,
      envelope.min_positions,
      envelope.max_positions,
      not_converged,
      wrong,
      not_converged + wrong == 0 ? "PASS" : "FAIL");
  return not_converged + wrong == 0 ? 0 : 1;
}
