#include "Dictionary.H"
#include "ConfinementLineStrength.H"
#include "FreezeBondProperties.H"
#include "FreezeBonding.H"
#include "HeatBalanceAreaCorrection.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace iceDEM;

namespace
{

FreezeBondProperties modelFrom(const std::string& text)
{
    return FreezeBondProperties::fromDictionary(Dictionary::parse(text, "freezeBondProperties"));
}

const std::string lineTable = R"(
    strengthModel confinementLine;
    confinementLineCoeffs
    {
        submersionTimes      (5 30 180);
        slopes               (3.3 3.3 3.3);
        intercepts           (264.5e3 58e3 0);
        shearToTensileRatios (0.4 0.6 0.9);
    }
)";

} // namespace


TEST(AreaCorrection, ReferenceHeatBalanceGives0p207)
{
    // physics.md section 5: 2.108 kJ/kgK x 18 K / 334 J/g = 11.4 % new ice.
    const double fraction = HeatBalanceAreaCorrection::newIceFraction(2108.0, 18.0, 334e3);
    EXPECT_NEAR(fraction, 0.1136, 5e-4);
    // A block with V/S = 2.82 cm grows 0.32 cm of ice per face.
    EXPECT_NEAR(HeatBalanceAreaCorrection::iceGrowth(fraction, 0.0282, 1.0), 0.0032, 2e-5);
    // A 3.94 cm band along a 5 cm contact against four 55 mm sphere bonds: 19.7 / 95.04 cm2.
    EXPECT_NEAR(HeatBalanceAreaCorrection::fromBand(0.0394, 0.05, 4, 0.0275), 0.207, 5e-4);
}


TEST(FreezeBondStrength, TensileLineAtTabulatedTimes)
{
    // 30 min: sigma_T = 3.3 p_c + 58 kPa (freezeBondTensile.csv fit); c_f = 1.
    const auto m30 = modelFrom("submersionTime 30;" + lineTable + "areaCorrection { model given; value 1; }");
    EXPECT_NEAR(m30.tensileAt(50e3), 3.3*50e3 + 58e3, 1e-6);
    const FreezeBondStrength s = m30.strength(100.0, 1e-3);     // 100 N on 10 cm2: 100 kPa
    EXPECT_NEAR(s.confinement, 100e3, 1e-6);
    EXPECT_NEAR(s.tensile, 3.3*100e3 + 58e3, 1e-6);
    EXPECT_NEAR(s.shear, 0.6*s.tensile, 1e-6);
    // 3 h: sigma_T = 3.3 p_c.
    const auto m180 = modelFrom("submersionTime 180;" + lineTable + "areaCorrection { model given; value 1; }");
    EXPECT_NEAR(m180.tensileAt(25e3), 82.5e3, 1e-6);
    // Tension at creation counts as no confinement.
    EXPECT_NEAR(m180.strength(-50.0, 1e-3).tensile, 0.0, 1e-12);
}


TEST(FreezeBondStrength, TimeInterpolatedInLogTime)
{
    // Halfway in log time between 30 and 180 min: sqrt(30 * 180) = 73.5 min.
    const auto m = modelFrom("submersionTime 73.48469228349535;" + lineTable + "areaCorrection { model given; value 1; }");
    const auto& line = dynamic_cast<const ConfinementLineStrength&>(m.strengthModel());
    EXPECT_NEAR(line.intercept(), 29e3, 1e-6);
    EXPECT_NEAR(line.shearToTensileRatio(), 0.75, 1e-12);
    // The peak after a few minutes is the strongest (physics.md section 5).
    const auto early = modelFrom("submersionTime 5;" + lineTable + "areaCorrection { model given; value 1; }");
    EXPECT_GT(early.tensileAt(25e3), m.tensileAt(25e3));
}


TEST(FreezeBondStrength, AreaCorrectionScalesPressureAndStrength)
{
    // A DEM bond of area A stands for c_f A of real frozen band: the same contact
    // force is a higher real pressure, and the bond carries c_f times the real stress.
    const double cf = 0.207;
    const auto m = modelFrom("submersionTime 30;" + lineTable + "areaCorrection { model given; value 0.207; }");
    const double area = M_PI*0.0275*0.0275;
    const double force = 10.0;
    const FreezeBondStrength s = m.strength(force, area);
    EXPECT_NEAR(s.confinement, force/(cf*area), 1e-9);
    EXPECT_NEAR(s.tensile, cf*(3.3*force/(cf*area) + 58e3), 1e-6);
}


TEST(FreezeBondStrength, FixedSetsFromTheRidgeData)
{
    // freezeBondSets.csv, 4 h: shear 88.8, tensile 26.9 kPa; with c_f 0.207 the shear
    // strength is the reference's 18.4 kPa.
    const auto m = modelFrom(R"(
        submersionTime 240;
        strengthModel fixedSet;
        fixedSetCoeffs
        {
            set 4h;
            sets { 2min { tensile 121.4e3; shear 364.1e3; } 4h { tensile 26.9e3; shear 88.8e3; } }
        }
        areaCorrection { model given; value 0.207; }
    )");
    const FreezeBondStrength s = m.strength(5.0, 1e-3);
    EXPECT_NEAR(s.shear, 18.38e3, 10.0);
    EXPECT_NEAR(s.tensile, 0.207*26.9e3, 1e-6);
}


TEST(FreezeBondStrength, BadInputNamesTheEntry)
{
    auto entryOf = [](const std::string& text)
    {
        try { modelFrom(text); }
        catch (const InputError& e) { return e.entry(); }
        return std::string("accepted");
    };
    const std::string area = "areaCorrection { model given; value 1; }";
    EXPECT_EQ(entryOf("submersionTime 300;" + lineTable + area), "submersionTime");
    EXPECT_EQ(entryOf("submersionTime 30; strengthModel linear;" + area), "strengthModel");
    EXPECT_EQ(entryOf("submersionTime 30;" + lineTable + "areaCorrection { model given; value -1; }"), "areaCorrection.value");
    EXPECT_EQ(entryOf("submersionTime 30;" + lineTable + "areaCorrection { model guess; }"), "areaCorrection.model");
    EXPECT_EQ(entryOf(R"(submersionTime 30; strengthModel fixedSet;
        fixedSetCoeffs { set 3h; sets { 4h { tensile 1; shear 1; } } } )" + area), "fixedSetCoeffs.set");
    EXPECT_EQ(entryOf(R"(submersionTime 30; strengthModel confinementLine;
        confinementLineCoeffs { submersionTimes (5 30); slopes (1); intercepts (0 0); shearToTensileRatios (1 1); } )" + area),
        "confinementLineCoeffs.slopes");
}


TEST(FreezeBonding, OnlyBetweenDifferentBlocksAndOnlyAtContacts)
{
    // Four spheres of radius 0.01 on a line: 0-1 same block touching, 1-2
    // different blocks overlapping by 1 mm, 2-3 different blocks 1 mm apart.
    IceProperties ice;
    ice.families[static_cast<int>(BondFamily::freeze)].distFactor = 1.0;
    std::vector<ParticleSpec> p(4);
    const double xs[4] = {0.0, 0.02, 0.039, 0.060};
    const int blocks[4] = {0, 0, 1, 2};
    for (int k = 0; k < 4; ++k)
    {
        p[k].position = Vec3(xs[k], 0, 0);
        p[k].radius = 0.01;
        p[k].block = blocks[k];
    }
    const auto model = modelFrom("submersionTime 180;" + lineTable + "areaCorrection { model given; value 1; }");
    const double kn = 1e5;
    const auto bonds = freezeBondsAtContacts(p, ice, model, kn);
    ASSERT_EQ(bonds.size(), 1u);
    EXPECT_EQ(bonds[0].pair.i, 1);
    EXPECT_EQ(bonds[0].pair.j, 2);
    EXPECT_EQ(bonds[0].pair.family, BondFamily::freeze);
    EXPECT_NEAR(bonds[0].contactForce, kn*0.001, 1e-9);
    const double area = M_PI*0.01*0.01;
    EXPECT_NEAR(bonds[0].strength.confinement, kn*0.001/area, 1e-6);
    EXPECT_NEAR(bonds[0].strength.tensile, 3.3*kn*0.001/area, 1e-6);
    const FreezeBondingStatistics s = freezeBondingStatistics(bonds, p);
    EXPECT_EQ(s.blockContacts, 1);
    EXPECT_DOUBLE_EQ(s.meanBondsPerBlockContact, 1.0);
}
