#include "ForceCurveAnalysis.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

using namespace iceDEM;

namespace
{

// Linear rise of slope k to peak P at travel P/k, then linear fall to zero over a further
// distance s, flat zero after; sampled every step, with the peak on a sample.
struct AnalyticCurve
{
    double k = 6.25e6;      // N/m
    double P = 1.2e5;       // N
    double s = 0.07;        // m
    double step = 2.0e-4;   // m

    double travelAtPeak() const { return P/k; }

    double force(double d) const
    {
        if (d <= travelAtPeak())
        {
            return k*d;
        }
        return std::max(0.0, P*(1.0 - (d - travelAtPeak())/s));
    }

    void sample(std::vector<double>& d, std::vector<double>& f, double end) const
    {
        const int nRise = static_cast<int>(std::lround(travelAtPeak()/step));
        const int n = static_cast<int>(std::lround(end/step));
        for (int i = 0; i <= n; ++i)
        {
            // The rise is sampled so that the peak travel is hit exactly.
            const double x = i <= nRise ? travelAtPeak()*i/nRise
                                        : travelAtPeak() + (i - nRise)*step;
            d.push_back(x);
            f.push_back(i == nRise ? P : force(x));
        }
    }
};

} // namespace


TEST(ForceCurveAnalysis, AnalyticCurveIsRecovered)
{
    const AnalyticCurve curve;
    std::vector<double> d, f;
    curve.sample(d, f, curve.travelAtPeak() + 1.5*curve.s);

    const ForceCurveResult r = analyseForceCurve(d, f);
    EXPECT_EQ(r.peakForce, curve.P);
    EXPECT_DOUBLE_EQ(r.travelAtPeak, curve.travelAtPeak());
    EXPECT_NEAR(r.elasticSlope, curve.k, 1e-9*curve.k);
    EXPECT_NEAR(r.slopeFitR2, 1.0, 1e-12);
    // 0.2 to 0.6 of the peak over 96 samples of the rise: about 38 samples.
    EXPECT_GE(r.slopeFitPoints, 35u);
    EXPECT_LE(r.slopeFitPoints, 41u);
    ASSERT_TRUE(r.halfLoadReached);
    EXPECT_NEAR(r.halfLoadTravelAfterPeak, curve.s/2, 1e-12);
}


TEST(ForceCurveAnalysis, FractionsAreParameters)
{
    const AnalyticCurve curve;
    std::vector<double> d, f;
    curve.sample(d, f, curve.travelAtPeak() + 1.5*curve.s);

    ForceCurveOptions options;
    options.lowFraction = 0.5;
    options.highFraction = 0.9;
    options.halfFraction = 0.25;
    const ForceCurveResult r = analyseForceCurve(d, f, options);
    EXPECT_NEAR(r.elasticSlope, curve.k, 1e-9*curve.k);
    ASSERT_TRUE(r.halfLoadReached);
    EXPECT_NEAR(r.halfLoadTravelAfterPeak, 0.75*curve.s, 1e-12);

    options.lowFraction = 0.7;
    options.highFraction = 0.6;
    EXPECT_THROW(analyseForceCurve(d, f, options), std::invalid_argument);
}


// Gaussian noise of 1 % of the peak on every sample. The tolerances cover the largest errors
// seen over ten seeds (peak +1.4 %: the largest noisy sample sits a few sigma high; travel at
// peak 7 %; slope 2.5 %; half-load travel 4.6 % of s, early: the first noisy crossing), with
// margin; this seed's errors are below 1.3 %.
TEST(ForceCurveAnalysis, NoisyCurveWithinTolerance)
{
    const AnalyticCurve curve;
    std::vector<double> d, f;
    curve.sample(d, f, curve.travelAtPeak() + 1.5*curve.s);
    std::mt19937 generator(20140321);
    std::normal_distribution<double> noise(0.0, 0.01*curve.P);
    for (double& value : f)
    {
        value += noise(generator);
    }

    const ForceCurveResult r = analyseForceCurve(d, f);
    EXPECT_NEAR(r.peakForce, curve.P, 0.03*curve.P);
    EXPECT_NEAR(r.travelAtPeak, curve.travelAtPeak(), 0.12*curve.travelAtPeak());
    EXPECT_NEAR(r.elasticSlope, curve.k, 0.04*curve.k);
    EXPECT_GT(r.slopeFitR2, 0.98);
    ASSERT_TRUE(r.halfLoadReached);
    EXPECT_NEAR(r.halfLoadTravelAfterPeak, curve.s/2, 0.08*curve.s);
}


TEST(ForceCurveAnalysis, CurveThatNeverHalvesReportsNotReached)
{
    const std::vector<double> d{0.0, 0.01, 0.02, 0.03, 0.04, 0.05};
    const std::vector<double> f{0.0, 50.0, 100.0, 80.0, 60.0, 55.0};
    const ForceCurveResult r = analyseForceCurve(d, f);
    EXPECT_EQ(r.peakForce, 100.0);
    EXPECT_EQ(r.travelAtPeak, 0.02);
    EXPECT_FALSE(r.halfLoadReached);
    EXPECT_TRUE(std::isnan(r.halfLoadTravelAfterPeak));
}


TEST(ForceCurveAnalysis, EarlierLoadDropIsNotFitted)
{
    // A partial drop from 75 to 30, then a second rise to the peak: only the first rise is
    // fitted, not the samples of the drop and of the second rise that lie in 20..60.
    const std::vector<double> d{0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0};
    const std::vector<double> f{0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 30.0, 50.0, 100.0, 40.0, 0.0};
    const ForceCurveResult r = analyseForceCurve(d, f);
    EXPECT_EQ(r.slopeFitPoints, 3u);
    EXPECT_NEAR(r.elasticSlope, 15.0, 1e-12);
    ASSERT_TRUE(r.halfLoadReached);
    EXPECT_NEAR(r.halfLoadTravelAfterPeak, 50.0/60.0, 1e-12);
}


TEST(ForceCurveAnalysis, RejectsBadInput)
{
    EXPECT_THROW(analyseForceCurve({0.0, 1.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(analyseForceCurve({0.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(analyseForceCurve({0.0, 1.0}, {0.0, -1.0}), std::invalid_argument);
    EXPECT_THROW(analyseForceCurve({0.0, 1.0}, {0.0, std::nan("")}), std::invalid_argument);
}


TEST(ForceCurveAnalysis, ContactOnsetInterpolatesTheFirstCrossing)
{
    const std::vector<double> d{0.0, 0.001, 0.002, 0.003, 0.004};
    const std::vector<double> f{0.0, 0.0, 20.0, 5.0, 40.0};
    EXPECT_NEAR(contactOnset(d, f, 10.0), 0.0015, 1e-15);
    EXPECT_EQ(contactOnset(d, f, -1.0), 0.0);
    EXPECT_TRUE(std::isnan(contactOnset(d, f, 50.0)));
}


TEST(ForceCurveFirstPeak, FirstMaximumFollowedByALargeDropNotTheGlobalOne)
{
    // Rises to 100, drops to 85 (15 %), rises again to 150 (an arch forms).
    const std::vector<double> d{0, 1, 2, 3, 4, 5, 6, 7};
    const std::vector<double> f{0, 50, 100, 95, 85, 120, 150, 70};
    const FirstPeak p = firstPeak(d, f, 0.1);
    EXPECT_EQ(p.force, 100.0);
    EXPECT_EQ(p.travel, 2.0);
    EXPECT_EQ(p.index, 2u);
    // A 5 % dip is noise, not a crack: the first peak is then 150.
    EXPECT_EQ(firstPeak(d, f, 0.2).force, 150.0);
}

TEST(ForceCurveFirstPeak, EarlyContactSpikeIsNotTheFirstPeak)
{
    // A 20 kN spike at first contact that drops by half, then the real rise.
    const std::vector<double> d{0, 1, 2, 3, 4, 5, 6};
    const std::vector<double> f{0, 20, 10, 60, 100, 80, 90};
    EXPECT_EQ(firstPeak(d, f, 0.1).force, 100.0);
    EXPECT_EQ(firstPeak(d, f, 0.1, 0.0).force, 20.0);
}

TEST(ForceCurveFirstPeak, MonotoneCurveGivesItsMaximum)
{
    const std::vector<double> d{0, 1, 2};
    const std::vector<double> f{0, 1, 2};
    EXPECT_EQ(firstPeak(d, f, 0.1).force, 2.0);
    EXPECT_THROW(firstPeak(d, {1.0}, 0.1), std::invalid_argument);
}
