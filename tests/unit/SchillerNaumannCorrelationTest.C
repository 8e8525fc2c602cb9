#include "SchillerNaumannCorrelation.H"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace iceDEM;

TEST(SchillerNaumannDrag, BothFormsAreOneCorrelation)
{
    // The coupling's C_d Re against the DEM side's C_d times Re: the same
    // correlation, equal to rounding.
    for (double Re : {1e-6, 0.01, 1.0, 10.0, 100.0, 500.0, 1000.0, 1e5})
    {
        EXPECT_NEAR(schillerNaumannDragCoefficientTimesRe(Re)/(schillerNaumannDragCoefficient(Re)*Re), 1.0, 1e-15)
            << "Re = " << Re;
    }
    // Re = 1: C_d = 24 (1 + 0.15) = 27.6; Stokes at Re -> 0, Newton's 0.44 above Re ~ 1000.
    EXPECT_NEAR(schillerNaumannDragCoefficientTimesRe(1.0), 27.6, 1e-12);
    EXPECT_DOUBLE_EQ(schillerNaumannDragCoefficientTimesRe(0.0), 24.0);
    EXPECT_DOUBLE_EQ(schillerNaumannDragCoefficientTimesRe(2000.0), 0.44*2000.0);
    EXPECT_DOUBLE_EQ(schillerNaumannStokesCorrection(0.0), 1.0);
}


TEST(SchillerNaumannDrag, EachFormKeepsItsEdges)
{
    // The DEM side refuses Re <= 0; the coupling's form is finite there and
    // passes a NaN of the viscous term on (OpenFOAM's max).
    EXPECT_THROW(schillerNaumannDragCoefficient(0.0), std::invalid_argument);
    EXPECT_THROW(schillerNaumannDragCoefficient(-1.0), std::invalid_argument);
    EXPECT_TRUE(std::isnan(schillerNaumannDragCoefficientTimesRe(-1.0)));
}
