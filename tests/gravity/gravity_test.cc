#include "mpcal/gravity.h"

#include <cmath>

#include <gtest/gtest.h>

#include "mpcal/error.h"

namespace mpcal {
namespace {

// Somigliana's closed form for WGS84 at zero height (NIMA TR8350.2 eq 4-1):
// γ_e = 9.7803253359, γ_p = 9.8321849378 m/s².
constexpr double kGammaEquatorMps2 = 9.7803253359;
constexpr double kGammaPoleMps2 = 9.8321849378;
constexpr double kReferenceTolerance = 1e-9;

TEST(NormalGravity, MatchesWgs84AtEquatorAndPole) {
  EXPECT_NEAR(NormalGravityMps2(0.0), kGammaEquatorMps2, kReferenceTolerance);
  EXPECT_NEAR(NormalGravityMps2(90.0), kGammaPoleMps2, kReferenceTolerance);
  EXPECT_NEAR(NormalGravityMps2(-90.0), kGammaPoleMps2, kReferenceTolerance);
}

TEST(NormalGravity, DecreasesWithHeightByTheFreeAirGradient) {
  // About −3.086e-6 m/s² per metre near the surface.
  const double g0 = NormalGravityMps2(45.0, 0.0);
  const double g1 = NormalGravityMps2(45.0, 1000.0);
  EXPECT_NEAR((g1 - g0) / 1000.0, -3.086e-6, 0.01e-6);
}

TEST(NormalGravity, RejectsImpossibleSites) {
  EXPECT_THROW(NormalGravityMps2(91.0), Error);
  EXPECT_THROW(NormalGravityMps2(std::nan("")), Error);
  EXPECT_THROW(NormalGravityMps2(45.0, 1e7), Error);
}

}  // namespace
}  // namespace mpcal
