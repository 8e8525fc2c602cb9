// Inertia scaling (issue 17): the time step grows with sqrt(s), the
// dictionary entry is range-checked and refused where it must not be used,
// and the kinetic-to-elastic ratio near the peak is what its comment says.
// The force and torque scaling inside LIGGGHTS: tests/integration/inertiaScalingFix.C.
#include "Dictionary.H"
#include "ForceCurveAnalysis.H"
#include "IceProperties.H"
#include "InertiaScaling.H"
#include "InputError.H"
#include "TimeStep.H"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

using namespace iceDEM;

namespace
{

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) \
        << "'" << (text) << "' does not contain '" << (part) << "'"

//- The cases' ice (cases/common/iceProperties), written to a temporary file and read.
IceProperties commonIce()
{
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "iceDEM_InertiaScalingTest_ice";
    std::ofstream(file) << R"(
FoamFile { version 2.0; format ascii; class dictionary; object iceProperties; }
material { density 917; youngsModulus 1.95e8; poissonsRatio 0.3; frictionCoefficient 0.3;
           rollingFrictionCoefficient 0.05; }
bondFamilies { ice { distFactor 1.1; youngsModulus 1.95e8; poissonsRatio 0.3; radiusMultiplier 1;
                     strengthModel strain; breakN 0.0081; beta 1.25; } }
damping { model hysteretic; hystereticCoeffs { alpha 0.1; } }
timeStep { factor 0.25; }
)";
    IceProperties p = IceProperties::read(file.string());
    std::filesystem::remove(file);
    return p;
}

Dictionary parse(const std::string& body)
{
    return Dictionary::parse("FoamFile { version 2.0; format ascii; class dictionary; object beamProperties; }\n" + body,
                             "constant/beamProperties");
}

} // namespace


TEST(InertiaScaling, timeStepGrowsWithTheSquareRootOfTheFactor)
{
    const IceProperties ice = commonIce();
    const TimeStepLimits one = timeStepLimits(ice, 0.02, 12);
    EXPECT_EQ(one.inertiaScaling, 1.0);
    // A factor of 1 is the step of before, bit for bit.
    const TimeStepLimits same = timeStepLimits(ice, 0.02, 12, 1.0);
    EXPECT_EQ(same.recommended, one.recommended);
    EXPECT_EQ(same.limit, one.limit);
    for (double s : {4.0, 10.0, 100.0, 1e4})
    {
        const TimeStepLimits scaled = timeStepLimits(ice, 0.02, 12, s);
        EXPECT_NEAR(scaled.recommended / one.recommended, std::sqrt(s), 1e-12 * std::sqrt(s)) << "s = " << s;
        EXPECT_NEAR(scaled.stiffestSpring / one.stiffestSpring, std::sqrt(s), 1e-12 * std::sqrt(s)) << "s = " << s;
        EXPECT_NEAR(scaled.limit / one.limit, std::sqrt(s), 1e-12 * std::sqrt(s)) << "s = " << s;
        EXPECT_EQ(scaled.stiffestSpringName, one.stiffestSpringName);
        // The same timeStep.factor is as safe (or unsafe) as before.
        EXPECT_DOUBLE_EQ(chooseTimeStep(ice, scaled, "iceProperties") / chooseTimeStep(ice, one, "iceProperties"),
                         std::sqrt(s));
    }
    EXPECT_THROW(timeStepLimits(ice, 0.02, 12, 0.5), std::invalid_argument);
}


TEST(InertiaScaling, unsafeStepNamesTheFactor)
{
    IceProperties ice = commonIce();
    ice.timeStep.factor = 10.0;     // far above the limit
    const TimeStepLimits scaled = timeStepLimits(ice, 0.02, 12, 100.0);
    try
    {
        chooseTimeStep(ice, scaled, "case/constant/iceProperties");
        FAIL() << "an unsafe step was accepted";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.entry(), "timeStep.factor");
        EXPECT_CONTAINS(e.what(), "inertia scaled by 100");
    }
}


TEST(InertiaScaling, entryIsOptionalAndRangeChecked)
{
    EXPECT_EQ(readInertiaScaling(parse("beam { length 1; }\n")), 1.0);
    EXPECT_EQ(readInertiaScaling(parse("inertiaScaling 1;\n")), 1.0);
    EXPECT_EQ(readInertiaScaling(parse("inertiaScaling 100;\n")), 100.0);
    EXPECT_EQ(readInertiaScaling(parse("test { inertiaScaling 10; }\n").subDict("test")), 10.0);
    for (const char* bad : {"inertiaScaling 0.5;\n", "inertiaScaling 0;\n", "inertiaScaling -10;\n",
                            "inertiaScaling 1e5;\n", "inertiaScaling fast;\n"})
    {
        try
        {
            readInertiaScaling(parse(bad));
            FAIL() << "accepted: " << bad;
        }
        catch (const InputError& e)
        {
            EXPECT_EQ(e.file(), "constant/beamProperties") << bad;
            EXPECT_CONTAINS(e.what(), "inertiaScaling");
        }
    }
    try
    {
        readInertiaScaling(parse("test { inertiaScaling 0.1; }\n").subDict("test"));
        FAIL() << "accepted 0.1";
    }
    catch (const InputError& e)
    {
        EXPECT_CONTAINS(e.what(), "test.inertiaScaling");
        EXPECT_CONTAINS(e.what(), "[1, 10000]");
    }
}


TEST(InertiaScaling, refusedWhereItMustNotBeUsed)
{
    const std::string why = "the heave period is the answer";
    EXPECT_NO_THROW(refuseInertiaScaling(parse("block { }\n"), "inertiaScaling", why));
    EXPECT_NO_THROW(refuseInertiaScaling(parse("inertiaScaling 1;\n"), "inertiaScaling", why));
    try
    {
        refuseInertiaScaling(parse("inertiaScaling 10;\n"), "inertiaScaling", why);
        FAIL() << "a factor was accepted where it is refused";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), "constant/beamProperties");
        EXPECT_CONTAINS(e.what(), "inertiaScaling");
        EXPECT_CONTAINS(e.what(), why);
    }
}


TEST(InertiaScaling, limitEntryOfTheRunControl)
{
    EXPECT_EQ(readMaxKineticToWorkRatio(parse("maxTravel 0.1;\n")), defaultMaxKineticToWorkRatio);
    EXPECT_EQ(readMaxKineticToWorkRatio(parse("maxKineticToWorkRatio 0.5;\n")), 0.5);
    EXPECT_THROW(readMaxKineticToWorkRatio(parse("maxKineticToWorkRatio 0;\n")), InputError);
}


TEST(InertiaScaling, kineticToElasticNearPeakIsTheMedianOverTheRiseToThePeak)
{
    // Peak 10 at index 5; samples from index 2 on reach half of it; index 6 is past the peak.
    const std::vector<double> force{1, 4, 5, 8, 9, 10, 9, 2};
    const std::vector<double> kinetic{100, 100, 1, 2, 300, 3, 1000, 1000};
    const std::vector<double> elastic{0, 1, 10, 20, 30, 30, 30, 0};
    // Ratios 0.1, 0.1, 10 (a piece flying off), 0.1 over indices 2-5: the median ignores the spike.
    EXPECT_DOUBLE_EQ(kineticToElasticNearPeak(force, kinetic, elastic), 0.1);
    // An odd count: 0.1, 10, 0.1 (indices 3-5 reach 0.8 of the peak).
    EXPECT_DOUBLE_EQ(kineticToElasticNearPeak(force, kinetic, elastic, 0.8), 0.1);
    // An even count, the mean of the middle two: indices 4 and 5 (ratios 10 and 0.1) reach 0.9 of the peak.
    EXPECT_DOUBLE_EQ(kineticToElasticNearPeak(force, kinetic, elastic, 0.9), 0.5 * (10.0 + 0.1));
    // Samples without elastic energy do not count; none at all gives 0.
    EXPECT_EQ(kineticToElasticNearPeak(force, kinetic, std::vector<double>(8, 0.0)), 0.0);
    EXPECT_EQ(kineticToElasticNearPeak({}, {}, {}), 0.0);
    EXPECT_THROW(kineticToElasticNearPeak(force, kinetic, {1, 2}), std::invalid_argument);
}


TEST(InertiaScaling, kineticToWorkIsTheMedianOverTheLoading)
{
    // Work by the trapezoidal rule from the first sample: 1, 3, 5 at samples 1-3.
    const std::vector<double> travel{0, 1, 2, 3};
    const std::vector<double> force{0, 2, 2, 2};
    const std::vector<double> kinetic{9, 0.1, 0.3, 10};
    // Ratios 0.1, 0.1, 2: the median; the first sample (no work yet) does not count.
    EXPECT_DOUBLE_EQ(kineticToWork(travel, force, kinetic), 0.1);
    // Samples before the platen has done work do not count either (force 0, or pulled back).
    EXPECT_DOUBLE_EQ(kineticToWork({0, 1, 2, 3, 4}, {0, 0, 2, 2, 2}, {5, 5, 0.1, 0.3, 10}), 0.1);
    EXPECT_EQ(kineticToWork({0, 1}, {0, 0}, {1, 1}), 0.0);
    EXPECT_EQ(kineticToWork({}, {}, {}), 0.0);
    EXPECT_THROW(kineticToWork(travel, force, {1, 2}), std::invalid_argument);
}
