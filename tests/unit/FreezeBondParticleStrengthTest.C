// particleStrengths of constant/freezeBondProperties: direct (the effective
// strengths c_f x real on the bonds, as before) and calibrated (the virtual
// tests' relation inverted, cases/common/freezeBondCalibration).

#include "CalibratedParticleStrength.H"
#include "Dictionary.H"
#include "DirectParticleStrength.H"
#include "FreezeBondProperties.H"
#include "IceProperties.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace iceDEM;

namespace
{

const std::string set4h = R"(
    submersionTime 240;
    strengthModel fixedSet;
    fixedSetCoeffs
    {
        set 4h;
        sets { 4h { tensile 26.9e3; shear 88.8e3; } iceRatio { tensile 195e3; shear 88.8e3; } }
    }
    areaCorrection { model given; value 0.197; }
)";

// A small relation: two ratios, shear with an intercept, tension without.
const std::string calibrated = R"(
    particleStrengths calibrated;
    calibratedCoeffs
    {
        ratios              (0.25 2.5);
        shearSlopes         (0.40 1.30);
        shearIntercepts     (400 200);
        tensileSlopes       (0.96 0.90);
        tensileIntercepts   (0 100);
        confinement             400;
        freezeToIceModulusRatio 1;
        relativeError           0.02;
    }
)";

// The same two ratios as measured points: S_eff at S_p 10, 20, 40 kPa (a bending
// relation, friction first), T_eff at T_p = rho S_p.
const std::string measuredPoints = R"(
    particleStrengths calibrated;
    calibratedCoeffs
    {
        ratios              (0.25 2.5);
        particleShears      (10e3 20e3 40e3);
        effectiveShears     (17e3 27e3 45e3    20e3 40e3 80e3);
        effectiveTensiles   (2e3 5e3 11e3      25e3 50e3 100e3);
        confinement             15000;
        freezeToIceModulusRatio 1;
        relativeError           0.05;
    }
)";

FreezeBondProperties propertiesFrom(const std::string& text)
{
    return FreezeBondProperties::fromDictionary(Dictionary::parse(text, "constant/freezeBondProperties"));
}

std::string messageOf(const std::function<void()>& f)
{
    try { f(); }
    catch (const InputError& e) { return e.what(); }
    return "accepted";
}

const double bondArea = M_PI*0.0275*0.0275;

} // namespace


TEST(FreezeBondParticleStrength, SelectedByNameDirectWhenAbsent)
{
    EXPECT_EQ(FreezeBondParticleStrength::names(), (std::vector<std::string>{"direct", "calibrated"}));
    const auto absent = propertiesFrom(set4h);
    EXPECT_NE(dynamic_cast<const DirectParticleStrength*>(&absent.particleStrength()), nullptr);
    const auto direct = propertiesFrom(set4h + "particleStrengths direct;");
    EXPECT_EQ(direct.particleStrength().name(), "direct");
    const auto c = propertiesFrom(set4h + calibrated);
    EXPECT_NE(dynamic_cast<const CalibratedParticleStrength*>(&c.particleStrength()), nullptr);
}


TEST(FreezeBondParticleStrength, DirectKeepsTheOldStrengthsAndSummary)
{
    // The strengths and the summary line before particleStrengths existed.
    for (const std::string& text : {set4h, set4h + "particleStrengths direct;"})
    {
        const FreezeBondStrength s = propertiesFrom(text).strength(0.5, bondArea);
        EXPECT_DOUBLE_EQ(s.tensile, 0.197*26.9e3);
        EXPECT_DOUBLE_EQ(s.shear, 0.197*88.8e3);
        EXPECT_DOUBLE_EQ(s.effectiveTensile, s.tensile);
        EXPECT_DOUBLE_EQ(s.effectiveShear, s.shear);
        EXPECT_EQ(propertiesFrom(text).summary(),
                  "freeze-bond set 4h: tensile 26.9 kPa, shear 88.8 kPa; area correction c_f = 0.197");
    }
}


TEST(FreezeBondParticleStrength, CalibratedMeetsTheShearAndKeepsTheRatio)
{
    const auto p = propertiesFrom(set4h + calibrated);
    const FreezeBondStrength s = p.strength(0.5, bondArea);
    EXPECT_DOUBLE_EQ(s.effectiveTensile, 0.197*26.9e3);
    EXPECT_DOUBLE_EQ(s.effectiveShear, 0.197*88.8e3);
    // rho = 26.9 / 88.8 = 0.3029: the relation interpolated between 0.25 and 2.5
    const double rho = 26.9/88.8;
    const double w = (rho - 0.25)/2.25;
    const double slope = 0.40 + w*(1.30 - 0.40), intercept = 400 + w*(200 - 400);
    EXPECT_NEAR(s.shear, (0.197*88.8e3 - intercept)/slope, 1e-9*s.shear);
    EXPECT_NEAR(s.tensile/s.shear, rho, 1e-12);
    // the relation gives back the effective shear; the tension is what it gives
    const BondStrengthPair back = p.particleStrength().effective({s.tensile, s.shear});
    EXPECT_NEAR(back.shear, s.effectiveShear, 1e-9*s.effectiveShear);
    const double tensileSlope = 0.96 + w*(0.90 - 0.96), tensileIntercept = w*100;
    EXPECT_NEAR(back.tensile, tensileSlope*s.tensile + tensileIntercept, 1e-9*back.tensile);
    EXPECT_NE(p.summary().find("particle strengths calibrated (virtual tests at 0.4 kPa on the bond area"),
              std::string::npos) << p.summary();
}


TEST(FreezeBondParticleStrength, MeasuredPointsAreInterpolatedAndInverted)
{
    const auto p = propertiesFrom(set4h + measuredPoints);
    const FreezeBondParticleStrength& relation = p.particleStrength();
    // At the first ratio the points themselves, between them the segment, beyond them the end segment.
    EXPECT_NEAR(relation.effective({0.25*20e3, 20e3}).shear, 27e3, 1e-6);
    EXPECT_NEAR(relation.effective({0.25*20e3, 20e3}).tensile, 5e3, 1e-6);
    EXPECT_NEAR(relation.effective({0.25*30e3, 30e3}).shear, 36e3, 1e-6);
    EXPECT_NEAR(relation.effective({0.25*50e3, 50e3}).shear, 54e3, 1e-6);
    EXPECT_NEAR(relation.particle({0.25*36e3, 36e3}).shear, 30e3, 1e-6);
    EXPECT_NEAR(relation.particle({0.25*36e3, 36e3}).tensile, 0.25*30e3, 1e-6);
    // Between the ratios each point's effective strength is interpolated, at the same S_p.
    const double rho = 1.375, w = 0.5;
    EXPECT_NEAR(relation.effective({rho*20e3, 20e3}).shear, 27e3 + w*(40e3 - 27e3), 1e-6);
    // The case's set (rho 0.3029) goes there and back.
    const FreezeBondStrength s = p.strength(0.5, bondArea);
    const BondStrengthPair back = relation.effective({s.tensile, s.shear});
    EXPECT_NEAR(back.shear, s.effectiveShear, 1e-9*s.effectiveShear);
    EXPECT_NEAR(s.tensile/s.shear, 26.9/88.8, 1e-12);
    EXPECT_NE(p.summary().find("the measured points"), std::string::npos) << p.summary();
}


TEST(FreezeBondParticleStrength, MeasuredPointsMustRise)
{
    std::string text = measuredPoints;
    const std::string row = "17e3 27e3 45e3";
    text.replace(text.find(row), row.size(), "17e3 27e3 26e3");
    const std::string m = messageOf([&] { propertiesFrom(set4h + text); });
    EXPECT_NE(m.find("entry 'calibratedCoeffs.effectiveShears'"), std::string::npos) << m;
    EXPECT_NE(m.find("row 1 (ratio 0.25) must rise"), std::string::npos) << m;
    std::string shortRow = measuredPoints;
    shortRow.replace(shortRow.find(row), row.size(), "17e3 27e3");
    const std::string n = messageOf([&] { propertiesFrom(set4h + shortRow); });
    EXPECT_NE(n.find("6 values"), std::string::npos) << n;
    // Friction alone gives more shear than asked: no particle strength can give less.
    std::string weak = set4h + measuredPoints;
    weak.replace(weak.find("tensile 26.9e3; shear 88.8e3"), 28, "tensile 2.69e3; shear 8.88e3");
    const std::string f = messageOf([&] { propertiesFrom(weak).strength(0.5, bondArea); });
    EXPECT_NE(f.find("with no bond strength at all"), std::string::npos) << f;
}


TEST(FreezeBondParticleStrength, BadNameNamesFileAndEntry)
{
    const std::string m = messageOf([] { propertiesFrom(set4h + "particleStrengths derived;"); });
    EXPECT_NE(m.find("constant/freezeBondProperties"), std::string::npos) << m;
    EXPECT_NE(m.find("entry 'particleStrengths'"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown value 'derived'; allowed: direct calibrated"), std::string::npos) << m;
    const std::string typo = messageOf([] { propertiesFrom(set4h + "particleStrength direct;"); });
    EXPECT_NE(typo.find("particleStrength"), std::string::npos) << typo;
    const std::string missing = messageOf([] { propertiesFrom(set4h + "particleStrengths calibrated;"); });
    EXPECT_NE(missing.find("entry 'calibratedCoeffs'"), std::string::npos) << missing;
}


TEST(FreezeBondParticleStrength, CalibratedRefusesWhatItCannotGive)
{
    // a ratio outside the table (the ice ratio 2.2 is inside, 10 is not)
    auto wide = propertiesFrom(set4h + calibrated);
    EXPECT_NO_THROW(wide.setSetStrengths(195e3, 88.8e3));
    EXPECT_NO_THROW(wide.strength(0.0, bondArea));
    wide.setSetStrengths(888e3, 88.8e3);
    const std::string ratio = messageOf([&] { wide.strength(0.0, bondArea); });
    EXPECT_NE(ratio.find("entry 'calibratedCoeffs.ratios'"), std::string::npos) << ratio;
    EXPECT_NE(ratio.find("ratio of 10 lies outside the calibrated ratios (0.25 to 2.5)"), std::string::npos) << ratio;
    // an effective shear below what the confinement alone gives (1 Pa set, c_f 0.197)
    auto weak = propertiesFrom(set4h + calibrated);
    weak.setSetStrengths(0.3, 1.0);
    const std::string low = messageOf([&] { weak.strength(0.0, bondArea); });
    EXPECT_NE(low.find("entry 'calibratedCoeffs.shearIntercepts'"), std::string::npos) << low;
    // bad tables
    const std::string order = messageOf([] {
        std::string t = calibrated;
        t.replace(t.find("(0.25 2.5)"), 10, "(2.5 0.25)");
        propertiesFrom(set4h + t);
    });
    EXPECT_NE(order.find("entry 'calibratedCoeffs.ratios'"), std::string::npos) << order;
    const std::string count = messageOf([] {
        std::string t = calibrated;
        t.replace(t.find("(0.40 1.30)"), 11, "(0.40)");
        propertiesFrom(set4h + t);
    });
    EXPECT_NE(count.find("entry 'calibratedCoeffs.shearSlopes'"), std::string::npos) << count;
}


TEST(FreezeBondParticleStrength, CalibratedHoldsForItsModulusRatioOnly)
{
    const auto p = propertiesFrom(set4h + calibrated);
    IceProperties ice;
    ice.families[static_cast<int>(BondFamily::ice)].youngsModulus = 1.95e8;
    ice.families[static_cast<int>(BondFamily::freeze)].youngsModulus = 1.95e8;
    EXPECT_NO_THROW(p.checkIce(ice, "constant/iceProperties"));
    ice.families[static_cast<int>(BondFamily::freeze)].youngsModulus = 5.4e8;
    const std::string m = messageOf([&] { p.checkIce(ice, "constant/iceProperties"); });
    EXPECT_NE(m.find("entry 'calibratedCoeffs.freezeToIceModulusRatio'"), std::string::npos) << m;
    EXPECT_NE(m.find("constant/iceProperties"), std::string::npos) << m;
    // direct holds for any
    EXPECT_NO_THROW(propertiesFrom(set4h).checkIce(ice, "constant/iceProperties"));
}


TEST(FreezeBondParticleStrength, CalibratedHoldsForItsCompressionModulusOnly)
{
    // A calibration without the entry was made with bonds as stiff in compression as in tension.
    const auto p = propertiesFrom(set4h + calibrated);
    IceProperties ice;
    ice.families[static_cast<int>(BondFamily::ice)].youngsModulus = 1.95e8;
    ice.families[static_cast<int>(BondFamily::freeze)].youngsModulus = 1.95e8;
    ice.families[static_cast<int>(BondFamily::freeze)].compressionModulus = 3.9e8;
    const std::string m = messageOf([&] { p.checkIce(ice, "constant/iceProperties"); });
    EXPECT_NE(m.find("entry 'calibratedCoeffs.freezeCompressionToIceModulusRatio'"), std::string::npos) << m;
    EXPECT_NE(m.find("in compression"), std::string::npos) << m;
    // One that records the ratio holds for it.
    std::string withRatio = calibrated;
    const std::string key = "freezeToIceModulusRatio 1;";
    withRatio.replace(withRatio.find(key), key.size(), key + " freezeCompressionToIceModulusRatio 2;");
    EXPECT_NO_THROW(propertiesFrom(set4h + withRatio).checkIce(ice, "constant/iceProperties"));
}


TEST(FreezeBondParticleStrength, CaseDictionariesReadAndMeetTheirShear)
{
    // cases/common/freezeBondProperties with each case's calibration (the case's #include)
    for (const char* name : {"ridgeFlexure", "keelBond", "rubblePunch", "rubbleBeam"})
    {
        const auto p = FreezeBondProperties::read
        (
            std::string(ICEDEM_SOURCE_DIR "/cases/") + name + "/constant/freezeBondProperties"
        );
        ASSERT_EQ(p.particleStrength().name(), "calibrated") << name;
        const FreezeBondStrength s = p.strength(0.0, bondArea);
        const BondStrengthPair back = p.particleStrength().effective({s.tensile, s.shear});
        EXPECT_NEAR(back.shear, s.effectiveShear, 1e-9*s.effectiveShear) << name;
        EXPECT_GT(s.shear, 0.0) << name;
    }
}
