// The freeze-bond strength and area-correction submodels against the numbers
// the single FreezeBondStrengthModel class gave before they were split
// (printed with %.17g from that class; same dictionaries, same calls).

#include "ConfinementLineStrength.H"
#include "Dictionary.H"
#include "FixedSetStrength.H"
#include "FreezeBondProperties.H"
#include "GivenAreaCorrection.H"
#include "HeatBalanceAreaCorrection.H"
#include "InputError.H"
#include "InterfaceAreaCorrection.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace iceDEM;

namespace
{

// cases/freezeBondTension's table.
const std::string line = R"(
    strengthModel confinementLine;
    confinementLineCoeffs
    {
        submersionTimes      (5 10 15 30 180);
        slopes               (3.6 3.6 3.6 3.6 3.97);
        intercepts           (256.5e3 205.5e3 92.5e3 58e3 -18e3);
        shearToTensileRatios (0.4 0.45 0.5 0.6 0.9);
    }
)";

const std::string set = R"(
    strengthModel fixedSet;
    fixedSetCoeffs
    {
        set 4h;
        sets { 2min { tensile 121.4e3; shear 364.1e3; } 4h { tensile 26.9e3; shear 88.8e3; } }
    }
)";

FreezeBondProperties propertiesFrom(const std::string& text)
{
    return FreezeBondProperties::fromDictionary(Dictionary::parse(text, "freezeBondProperties"));
}

const double bondArea = M_PI*0.0275*0.0275;

struct Expected
{
    double force, confinement, tensile, shear;
};

void expectStrengths(const FreezeBondProperties& p, const std::vector<Expected>& rows)
{
    for (const Expected& e : rows)
    {
        const FreezeBondStrength s = p.strength(e.force, bondArea);
        EXPECT_DOUBLE_EQ(s.confinement, e.confinement) << "F = " << e.force;
        EXPECT_DOUBLE_EQ(s.tensile, e.tensile) << "F = " << e.force;
        EXPECT_DOUBLE_EQ(s.shear, e.shear) << "F = " << e.force;
    }
}

} // namespace


TEST(FreezeBondModels, SelectedByName)
{
    EXPECT_EQ(FreezeBondStrengthModel::names(), (std::vector<std::string>{"confinementLine", "fixedSet"}));
    EXPECT_EQ(FreezeBondAreaCorrection::names(), (std::vector<std::string>{"given", "heatBalance", "interface"}));
    const auto a = propertiesFrom("submersionTime 30;" + line + "areaCorrection { model heatBalance; }");
    EXPECT_NE(dynamic_cast<const ConfinementLineStrength*>(&a.strengthModel()), nullptr);
    EXPECT_NE(dynamic_cast<const HeatBalanceAreaCorrection*>(&a.areaCorrection()), nullptr);
    const auto b = propertiesFrom("submersionTime 30;" + set + "areaCorrection { model interface; }");
    EXPECT_NE(dynamic_cast<const FixedSetStrength*>(&b.strengthModel()), nullptr);
    EXPECT_NE(dynamic_cast<const InterfaceAreaCorrection*>(&b.areaCorrection()), nullptr);
    const auto c = propertiesFrom("submersionTime 30;" + set + "areaCorrection { model given; value 0.5; }");
    EXPECT_NE(dynamic_cast<const GivenAreaCorrection*>(&c.areaCorrection()), nullptr);
}


TEST(FreezeBondModels, UnknownNamesListTheAllowedOnes)
{
    auto messageOf = [](const std::string& text)
    {
        try { propertiesFrom(text); }
        catch (const InputError& e) { return std::string(e.what()); }
        return std::string("accepted");
    };
    const std::string strength = messageOf("submersionTime 30; strengthModel linear; areaCorrection { model given; value 1; }");
    EXPECT_NE(strength.find("entry 'strengthModel'"), std::string::npos) << strength;
    EXPECT_NE(strength.find("unknown value 'linear'; allowed: confinementLine fixedSet"), std::string::npos) << strength;
    const std::string area = messageOf("submersionTime 30;" + set + "areaCorrection { model guess; }");
    EXPECT_NE(area.find("entry 'areaCorrection.model'"), std::string::npos) << area;
    EXPECT_NE(area.find("unknown value 'guess'; allowed: given heatBalance interface"), std::string::npos) << area;
}


TEST(FreezeBondModels, ConfinementLineWithGivenAreaCorrection)
{
    const auto p = propertiesFrom("submersionTime 12;" + line + "areaCorrection { model given; value 0.207; }");
    expectStrengths(p, {
        {-5.0, 0.0, 32020.496231770161, 15129.14058022823},
        {0.0, 0.0, 32020.496231770161, 15129.14058022823},
        {3.0, 6100.0816612057151, 36566.277085700662, 17276.94482061937},
        {100.0, 203336.05537352382, 183546.52469612009, 86722.615259932849}});
    EXPECT_DOUBLE_EQ(p.tensileAt(40e3), 298688.38759309257);
    EXPECT_DOUBLE_EQ(p.areaCorrection().value(), 0.207);
    const auto& l = dynamic_cast<const ConfinementLineStrength&>(p.strengthModel());
    EXPECT_DOUBLE_EQ(l.slope(), 3.6);
    EXPECT_DOUBLE_EQ(l.intercept(), 154688.38759309257);
    EXPECT_DOUBLE_EQ(l.shearToTensileRatio(), 0.47248301433933959);
    EXPECT_EQ(p.summary(), "freeze-bonds after 12 min: sigma_T = 3.6 p_c + 154.688 kPa, "
                           "shear/tensile 0.472483; area correction c_f = 0.207");
}


TEST(FreezeBondModels, ConfinementLineWithInterfaceAreaCorrection)
{
    auto p = propertiesFrom("submersionTime 100;" + line + "areaCorrection { model interface; }");
    // c_f 1 until the specimen sets it.
    expectStrengths(p, {
        {-5.0, 0.0, 6931.798770851201, 5556.4259513651768},
        {3.0, 1262.7169038695829, 11791.518203053227, 9451.9041760057262},
        {100.0, 42090.563462319427, 168922.4465109187, 135405.70010605012}});
    EXPECT_EQ(p.summary(), "freeze-bonds after 100 min: sigma_T = 3.84862 p_c + 6.9318 kPa, "
                           "shear/tensile 0.801585; area correction c_f = 1");
    dynamic_cast<InterfaceAreaCorrection&>(p.areaCorrection()).setFromInterface(0.7, 2.0);
    expectStrengths(p, {
        {0.0, 0.0, 2426.1295697979203, 1944.7490829778117},
        {3.0, 3607.7625824845227, 7285.8490019999454, 5840.2273076183601},
        {100.0, 120258.75274948409, 164416.77730986546, 131794.0232376628}});
    EXPECT_DOUBLE_EQ(p.tensileAt(40e3), 160876.65901021176);
    p.setSubmersionTime(7.5);
    expectStrengths(p, {
        {0.0, 0.0, 79333.419362127359, 34053.721513892458},
        {3.0, 3607.7625824845227, 83879.20021605787, 36004.989422266932},
        {100.0, 120258.75274948409, 230859.44782647729, 99095.985126375002}});
    EXPECT_DOUBLE_EQ(p.submersionTime(), 7.5);
    EXPECT_EQ(p.summary(), "freeze-bonds after 7.5 min: sigma_T = 3.6 p_c + 226.667 kPa, "
                           "shear/tensile 0.429248; area correction c_f = 0.35");
    EXPECT_THROW(p.setSubmersionTime(200.0), InputError);
    EXPECT_THROW(p.setSubmersionTime(0.0), InputError);
}


TEST(FreezeBondModels, FixedSetWithHeatBalanceAreaCorrection)
{
    auto p = propertiesFrom("submersionTime 240;" + set + "areaCorrection { model heatBalance; }");
    expectStrengths(p, {
        {-5.0, 0.0, 26900.0, 88800.0},
        {100.0, 42090.563462319427, 26900.0, 88800.0}});
    auto& heatBalance = dynamic_cast<HeatBalanceAreaCorrection&>(p.areaCorrection());
    EXPECT_DOUBLE_EQ(heatBalance.forBlocks(0.0282, 1.0, 0.0275), 0.20732210859930472);
    heatBalance.setFromBlocks(0.0282, 1.0, 0.0275);
    expectStrengths(p, {
        {0.0, 0.0, 5576.9647213212966, 18410.20324361826},
        {3.0, 6090.6041926771022, 5576.9647213212966, 18410.20324361826},
        {100.0, 203020.13975590339, 5576.9647213212966, 18410.20324361826}});
    EXPECT_DOUBLE_EQ(p.tensileAt(40e3), 26900.0);
    EXPECT_EQ(p.summary(), "freeze-bond set 4h: tensile 26.9 kPa, shear 88.8 kPa; area correction c_f = 0.207322");

    const auto custom = propertiesFrom("submersionTime 240;" + set + R"(areaCorrection { model heatBalance;
        heatCapacity 2000; temperatureDrop 10; latentHeat 300e3; contactLength 0.04;
        bandWidthPerGrowth 10; bondsPerContact 3; })");
    EXPECT_DOUBLE_EQ(dynamic_cast<const HeatBalanceAreaCorrection&>(custom.areaCorrection()).forBlocks(0.05, 0.9, 0.02),
                     0.3929751681281366);
}


TEST(FreezeBondModels, FixedSetWithGivenAreaCorrectionAndOverride)
{
    auto p = propertiesFrom("submersionTime 240;" + set + "areaCorrection { model given; value 0.197; }");
    expectStrengths(p, {
        {-5.0, 0.0, 5299.3000000000002, 17493.600000000002},
        {3.0, 6409.7304764953442, 5299.3000000000002, 17493.600000000002},
        {100.0, 213657.68254984482, 5299.3000000000002, 17493.600000000002}});
    EXPECT_EQ(p.summary(), "freeze-bond set 4h: tensile 26.9 kPa, shear 88.8 kPa; area correction c_f = 0.197");
    p.setSetStrengths(150e3, 200e3);
    expectStrengths(p, {{100.0, 213657.68254984482, 29550.0, 39400.0}});
    EXPECT_DOUBLE_EQ(p.tensileAt(40e3), 150e3);
    EXPECT_EQ(p.summary(), "freeze-bond set 4h: tensile 150 kPa, shear 200 kPa; area correction c_f = 0.197");

    // Only a fixed set has strengths to override.
    auto l = propertiesFrom("submersionTime 30;" + line + "areaCorrection { model given; value 1; }");
    try
    {
        l.setSetStrengths(1e3, 1e3);
        FAIL() << "override accepted";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.entry(), "strengthModel");
    }
}
