#include "IceProperties.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace iceDEM;

namespace
{

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) \
        << "'" << (text) << "' does not contain '" << (part) << "'"

//- Smallest complete file: only required entries, strain model, freeze family left out.
const std::string minimalText = R"(
FoamFile { version 2.0; format ascii; class dictionary; object iceProperties; }
material
{
    density 917;
    youngsModulus 4e8;
    poissonsRatio 0.3;
    frictionCoefficient 0.2;
    rollingFrictionCoefficient 0.05;
}
bondFamilies
{
    ice
    {
        distFactor 1.1;
        youngsModulus 5.4e8;
        poissonsRatio 0.3;
        radiusMultiplier 1;
        strengthModel strain;
        breakN 0.0037;
        beta 1.25;
    }
}
damping
{
    model hysteretic;
    hystereticCoeffs { alpha 0.1; }
}
)";

//- Temporary directory for this test's files, removed at the end of the test.
class IcePropertiesFiles : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ = std::filesystem::temp_directory_path()
            / ("iceDEM_IcePropertiesTest_"
             + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(dir_);
    }

    void TearDown() override
    {
        std::filesystem::remove_all(dir_);
    }

    std::string write(const std::string& text, const std::string& name = "iceProperties")
    {
        const std::string file = (dir_ / name).string();
        std::ofstream out(file);
        out << text;
        return file;
    }

    //- minimalText with `from` (which must occur exactly once) replaced by `to`.
    static std::string edited(const std::string& from, const std::string& to)
    {
        const std::size_t at = minimalText.find(from);
        EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the test text";
        EXPECT_EQ(minimalText.find(from, at + 1), std::string::npos) << "'" << from << "' twice";
        std::string text = minimalText;
        if (at != std::string::npos) text.replace(at, from.size(), to);
        return text;
    }

    //- Message of the InputError that reading `text` throws.
    std::string errorReading(const std::string& text)
    {
        const std::string file = write(text);
        try
        {
            IceProperties::read(file);
        }
        catch (const InputError& e)
        {
            EXPECT_EQ(e.file(), file);
            return e.what();
        }
        ADD_FAILURE() << "expected an InputError";
        return "";
    }

    std::filesystem::path dir_;
};

} // namespace


TEST_F(IcePropertiesFiles, ValidFileRoundTrips)
{
    const IceProperties p =
        IceProperties::read(ICEDEM_SOURCE_DIR "/tests/unit/data/iceProperties.valid");

    EXPECT_DOUBLE_EQ(p.material.density, 917);
    EXPECT_DOUBLE_EQ(p.material.youngsModulus, 5.4e8);
    EXPECT_DOUBLE_EQ(p.material.poissonsRatio, 0.3);
    EXPECT_DOUBLE_EQ(p.material.frictionCoefficient, 0.3);
    EXPECT_DOUBLE_EQ(p.material.rollingFrictionCoefficient, 0.05);

    const BondFamilyParameters& ice = p.family(BondFamily::ice);
    EXPECT_DOUBLE_EQ(ice.distFactor, 1.1);
    EXPECT_DOUBLE_EQ(ice.youngsModulus, 5.4e8);
    EXPECT_DOUBLE_EQ(ice.poissonsRatio, 0.3);
    EXPECT_DOUBLE_EQ(ice.radiusMultiplier, 1);
    EXPECT_EQ(ice.strengthModel, StrengthModel::strain);
    EXPECT_DOUBLE_EQ(ice.breakN, 0.0037);
    EXPECT_DOUBLE_EQ(ice.beta, 1.25);
    EXPECT_DOUBLE_EQ(ice.tensileStrength, 0);
    EXPECT_DOUBLE_EQ(ice.shearStrength, 0);
    EXPECT_DOUBLE_EQ(ice.twistStrengthFactor, 1);
    EXPECT_DOUBLE_EQ(ice.bendingStrengthFactor, 1);
    EXPECT_EQ(ice.criterion, BreakageCriterion::separate);
    EXPECT_FALSE(ice.unbreakable);

    const BondFamilyParameters& freeze = p.family(BondFamily::freeze);
    EXPECT_DOUBLE_EQ(freeze.distFactor, 1.05);
    EXPECT_DOUBLE_EQ(freeze.youngsModulus, 1e8);
    EXPECT_DOUBLE_EQ(freeze.poissonsRatio, 0.25);
    EXPECT_DOUBLE_EQ(freeze.radiusMultiplier, 0.8);
    EXPECT_EQ(freeze.strengthModel, StrengthModel::stress);
    EXPECT_DOUBLE_EQ(freeze.tensileStrength, 2.2e4);
    EXPECT_DOUBLE_EQ(freeze.shearStrength, 1.5e4);
    EXPECT_DOUBLE_EQ(freeze.twistStrengthFactor, 0.5);
    EXPECT_DOUBLE_EQ(freeze.bendingStrengthFactor, 2);
    EXPECT_EQ(freeze.criterion, BreakageCriterion::combined);
    EXPECT_TRUE(freeze.unbreakable);

    EXPECT_EQ(p.damping.model, DampingModel::hysteretic);
    EXPECT_DOUBLE_EQ(p.damping.alpha, 0.1);
    EXPECT_DOUBLE_EQ(p.damping.dampingRatio, 0.05);
    EXPECT_DOUBLE_EQ(p.timeStep.factor, 0.1);
    EXPECT_DOUBLE_EQ(p.timeStep.deltaT, 0);
    EXPECT_EQ(p.maxBondsPerParticle, 16);
}


TEST_F(IcePropertiesFiles, OptionalEntriesTakeDefaultsAndFreezeCopiesIce)
{
    const IceProperties p = IceProperties::read(write(minimalText));
    EXPECT_DOUBLE_EQ(p.material.youngsModulus, 4e8);
    EXPECT_DOUBLE_EQ(p.material.frictionCoefficient, 0.2);

    const BondFamilyParameters& ice = p.family(BondFamily::ice);
    const BondFamilyParameters& freeze = p.family(BondFamily::freeze);
    EXPECT_DOUBLE_EQ(ice.twistStrengthFactor, 1);
    EXPECT_DOUBLE_EQ(ice.bendingStrengthFactor, 1);
    EXPECT_EQ(ice.criterion, BreakageCriterion::separate);
    EXPECT_FALSE(ice.unbreakable);
    EXPECT_DOUBLE_EQ(freeze.distFactor, ice.distFactor);
    EXPECT_DOUBLE_EQ(freeze.youngsModulus, ice.youngsModulus);
    EXPECT_EQ(freeze.strengthModel, ice.strengthModel);
    EXPECT_DOUBLE_EQ(freeze.breakN, ice.breakN);
    EXPECT_DOUBLE_EQ(freeze.beta, ice.beta);

    EXPECT_DOUBLE_EQ(p.timeStep.factor, 0.1);
    EXPECT_DOUBLE_EQ(p.timeStep.deltaT, 0);
    EXPECT_EQ(p.maxBondsPerParticle, 16);
}


TEST_F(IcePropertiesFiles, OtherChoicesAreRead)
{
    std::string text = edited
    (
        "    model hysteretic;\n    hystereticCoeffs { alpha 0.1; }",
        "    model viscous;\n    viscousCoeffs { dampingRatio 0.2; }"
    );
    text += "timeStep { deltaT 1e-6; factor 0.05; }\nmaxBondsPerParticle 64;\n";
    const IceProperties p = IceProperties::read(write(text));
    EXPECT_EQ(p.damping.model, DampingModel::viscous);
    EXPECT_DOUBLE_EQ(p.damping.dampingRatio, 0.2);
    EXPECT_DOUBLE_EQ(p.timeStep.factor, 0.05);
    EXPECT_DOUBLE_EQ(p.timeStep.deltaT, 1e-6);
    EXPECT_EQ(p.maxBondsPerParticle, 64);

    const IceProperties none = IceProperties::read
    (
        write(edited("model hysteretic;\n    hystereticCoeffs { alpha 0.1; }", "model none;"), "none")
    );
    EXPECT_EQ(none.damping.model, DampingModel::none);
}


TEST_F(IcePropertiesFiles, MissingFamilyModulus)
{
    const std::string msg = errorReading(edited("        youngsModulus 5.4e8;\n", ""));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.youngsModulus': missing; expected a positive number in Pa");
}


TEST_F(IcePropertiesFiles, NegativeMaterialModulus)
{
    const std::string msg = errorReading(edited("youngsModulus 4e8;", "youngsModulus -4e8;"));
    EXPECT_CONTAINS(msg, "entry 'material.youngsModulus'");
    EXPECT_CONTAINS(msg, "-4e+08 is out of range; expected a positive number in Pa");
}


TEST_F(IcePropertiesFiles, NegativeFamilyModulus)
{
    const std::string msg = errorReading(edited("youngsModulus 5.4e8;", "youngsModulus -1;"));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.youngsModulus'");
    EXPECT_CONTAINS(msg, "out of range");
}


TEST_F(IcePropertiesFiles, CompressionModulusIsOptionalAndPositive)
{
    const IceProperties same = IceProperties::read(write(minimalText));
    EXPECT_DOUBLE_EQ(same.family(BondFamily::ice).compressionModulusOrYoungs(),
                     same.family(BondFamily::ice).youngsModulus);
    const IceProperties given = IceProperties::read
    (
        write(edited("youngsModulus 5.4e8;", "youngsModulus 5.4e8; compressionModulus 6e8;"), "given")
    );
    EXPECT_DOUBLE_EQ(given.family(BondFamily::ice).compressionModulusOrYoungs(), 6e8);
    const std::string msg = errorReading(edited("youngsModulus 5.4e8;", "youngsModulus 5.4e8; compressionModulus 0;"));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.compressionModulus'");
    EXPECT_CONTAINS(msg, "out of range");
}


TEST_F(IcePropertiesFiles, DistFactorBelowOne)
{
    const std::string msg = errorReading(edited("distFactor 1.1;", "distFactor 0.9;"));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.distFactor'");
    EXPECT_CONTAINS(msg, "0.9 is out of range; expected a number >= 1");
}


TEST_F(IcePropertiesFiles, UnknownDampingModel)
{
    const std::string msg = errorReading(edited("model hysteretic;", "model foo;"));
    EXPECT_CONTAINS(msg, "entry 'damping.model'");
    EXPECT_CONTAINS(msg, "unknown value 'foo'; allowed: none hysteretic viscous");
}


TEST_F(IcePropertiesFiles, StressModelWithoutTensileStrength)
{
    const std::string msg = errorReading
    (
        edited("strengthModel strain;", "strengthModel stress;\n        shearStrength 1e5;")
    );
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.tensileStrength': missing");
}


TEST_F(IcePropertiesFiles, StressModelDoesNotNeedStrainEntries)
{
    const IceProperties p = IceProperties::read
    (
        write
        (
            edited
            (
                "strengthModel strain;\n        breakN 0.0037;\n        beta 1.25;",
                "strengthModel stress;\n        tensileStrength 6e5;\n        shearStrength 7e5;"
            )
        )
    );
    EXPECT_EQ(p.family(BondFamily::ice).strengthModel, StrengthModel::stress);
    EXPECT_DOUBLE_EQ(p.family(BondFamily::ice).tensileStrength, 6e5);
    EXPECT_DOUBLE_EQ(p.family(BondFamily::ice).shearStrength, 7e5);
}


TEST_F(IcePropertiesFiles, MisspeltKeywords)
{
    std::string msg = errorReading(edited("radiusMultiplier 1;", "radiusMultipler 1;"));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.ice.radiusMultipler'");
    EXPECT_CONTAINS(msg, "unknown keyword (did you mean 'radiusMultiplier'?)");
    EXPECT_CONTAINS(msg, "allowed: distFactor youngsModulus");

    msg = errorReading(edited("density 917;", "densty 917;"));
    EXPECT_CONTAINS(msg, "entry 'material.densty'");

    msg = errorReading(edited("hystereticCoeffs", "hystereticCoefs"));
    EXPECT_CONTAINS(msg, "entry 'damping.hystereticCoefs'");

    msg = errorReading(edited("    ice\n", "    ice\n    {\n    }\n    frieze\n"));
    EXPECT_CONTAINS(msg, "entry 'bondFamilies.frieze'");

    msg = errorReading(minimalText + "maxBondPerParticle 8;\n");
    EXPECT_CONTAINS(msg, "entry 'maxBondPerParticle'");
    EXPECT_CONTAINS(msg, "did you mean 'maxBondsPerParticle'?");
}


TEST_F(IcePropertiesFiles, MissingFile)
{
    const std::string file = (dir_ / "noSuchFile").string();
    try
    {
        IceProperties::read(file);
        ADD_FAILURE() << "expected an InputError";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), file);
        EXPECT_CONTAINS(e.what(), "cannot open the file");
    }
}


TEST_F(IcePropertiesFiles, OtherOutOfRangeAndMissingEntries)
{
    struct Case { std::string from; std::string to; std::string part; };
    const std::vector<Case> cases =
    {
        {"    density 917;\n", "", "entry 'material.density': missing"},
        {"density 917;", "density nan;", "entry 'material.density': line 5: 'nan' is not a finite"},
        {"poissonsRatio 0.3;\n    friction", "poissonsRatio 0.5;\n    friction",
            "entry 'material.poissonsRatio'"},
        {"frictionCoefficient 0.2;", "frictionCoefficient -0.1;", "expected a number >= 0"},
        {"radiusMultiplier 1;", "radiusMultiplier 0;", "entry 'bondFamilies.ice.radiusMultiplier'"},
        {"strengthModel strain;", "strengthModel brittle;", "unknown value 'brittle'; allowed: strain stress"},
        {"breakN 0.0037;", "breakN 0;", "entry 'bondFamilies.ice.breakN'"},
        {"beta 1.25;", "", "entry 'bondFamilies.ice.beta': missing"},
        {"beta 1.25;", "beta 1.25; breakageCriterion both;", "allowed: separate combined"},
        {"beta 1.25;", "beta 1.25; unbreakable maybe;", "entry 'bondFamilies.ice.unbreakable'"},
        {"beta 1.25;", "beta 1.25; twistStrengthFactor 0;", "entry 'bondFamilies.ice.twistStrengthFactor'"},
        {"beta 1.25;", "beta 1.25; tensileStrength -5;", "entry 'bondFamilies.ice.tensileStrength'"},
        {"alpha 0.1;", "alpha 1;", "entry 'damping.hystereticCoeffs.alpha'"},
        {"    hystereticCoeffs { alpha 0.1; }\n", "", "entry 'damping.hystereticCoeffs': missing"},
        {"model hysteretic;", "model viscous;", "entry 'damping.viscousCoeffs': missing"},
        {"alpha 0.1;", "alpha 0.1; beta 1;", "entry 'damping.hystereticCoeffs.beta'"},
        {"damping\n{\n    model hysteretic;", "damping\n{\n", "entry 'damping.model': missing"},
    };
    for (const Case& c : cases)
    {
        SCOPED_TRACE(c.to);
        EXPECT_CONTAINS(errorReading(edited(c.from, c.to)), c.part);
    }

    struct Extra { std::string text; std::string part; };
    const std::vector<Extra> extras =
    {
        {"timeStep { factor 0; }\n", "entry 'timeStep.factor'"},
        {"timeStep { deltaT -1e-6; }\n", "entry 'timeStep.deltaT'"},
        {"timeStep { dt 1e-6; }\n", "entry 'timeStep.dt'"},
        {"maxBondsPerParticle 65;\n", "expected an integer in [1, 64]"},
        {"maxBondsPerParticle 0;\n", "expected an integer in [1, 64]"},
        {"maxBondsPerParticle 1.5;\n", "'1.5' is not an integer"},
        {"bondFamilies2 { }\n", "entry 'bondFamilies2': line 29: unknown keyword"},
    };
    for (const Extra& e : extras)
    {
        SCOPED_TRACE(e.text);
        EXPECT_CONTAINS(errorReading(minimalText + e.text), e.part);
    }
}


TEST_F(IcePropertiesFiles, MissingSections)
{
    EXPECT_CONTAINS
    (
        errorReading(edited("damping\n{\n    model hysteretic;\n    hystereticCoeffs { alpha 0.1; }\n}\n", "")),
        "entry 'damping': missing; expected a sub-dictionary"
    );
    EXPECT_CONTAINS
    (
        errorReading(edited("    ice\n", "    freeze\n")),
        "entry 'bondFamilies.ice': missing"
    );
}


TEST_F(IcePropertiesFiles, MissingSemicolonNamesLine)
{
    const std::string msg = errorReading(edited("density 917;", "density 917"));
    EXPECT_CONTAINS(msg, "iceProperties");
    EXPECT_CONTAINS(msg, "entry 'material.density': line 5:");
}


TEST_F(IcePropertiesFiles, SyntaxErrorNamesFileAndLine)
{
    const std::string msg = errorReading(minimalText + "\ntimeStep\n{\n    factor 0.1;\n");
    EXPECT_CONTAINS(msg, "/iceProperties: entry 'timeStep': line 31: '{' of 'timeStep' is never closed");
}


TEST(IcePropertiesTypes, ToStringGivesTheDictionaryWords)
{
    EXPECT_EQ(toString(BondFamily::ice), "ice");
    EXPECT_EQ(toString(BondFamily::freeze), "freeze");
    EXPECT_EQ(toString(BreakMode::none), "none");
    EXPECT_EQ(toString(BreakMode::tension), "tension");
    EXPECT_EQ(toString(BreakMode::shear), "shear");
    EXPECT_EQ(toString(BreakMode::twist), "twist");
    EXPECT_EQ(toString(BreakMode::bending), "bending");
    EXPECT_EQ(toString(StrengthModel::stress), "stress");
    EXPECT_EQ(toString(StrengthModel::strain), "strain");
    EXPECT_EQ(toString(BreakageCriterion::separate), "separate");
    EXPECT_EQ(toString(BreakageCriterion::combined), "combined");
    EXPECT_EQ(toString(DampingModel::none), "none");
    EXPECT_EQ(toString(DampingModel::hysteretic), "hysteretic");
    EXPECT_EQ(toString(DampingModel::viscous), "viscous");
}
