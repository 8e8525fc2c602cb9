#include "WaterProperties.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace iceDEM;

namespace
{

const std::string header =
    "FoamFile { version 2.0; format ascii; class dictionary; object couplingProperties; }\n";

const std::string hydrostaticText = header + R"(
waterLevel hydrostatic;
hydrostatic
{
    surfaceLevel          0.45;
    rho                   1000;
    mu                    1.79e-3;
    addedMassCoefficient  0.5;
    drag                  SchillerNaumann;
}
)";

const std::string gravityText =
    "FoamFile { version 2.0; format ascii; class uniformDimensionedVectorField; object g; }\n"
    "dimensions [0 1 -2 0 0 0 0];\nvalue (0 0 -9.81);\n";

class WaterPropertiesFiles : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ = std::filesystem::temp_directory_path()
            / ("iceDEM_WaterPropertiesTest_"
             + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(dir_ / "constant");
    }

    void TearDown() override
    {
        std::filesystem::remove_all(dir_);
    }

    std::string write(const std::string& name, const std::string& text)
    {
        const std::string file = (dir_ / "constant" / name).string();
        std::ofstream(file) << text;
        return file;
    }

    //- The error text of reading this couplingProperties (with a valid g).
    std::string errorOf(const std::string& coupling, const std::string& gravity = gravityText)
    {
        write("couplingProperties", coupling);
        write("g", gravity);
        try
        {
            WaterProperties::readCase(dir_.string());
        }
        catch (const InputError& e)
        {
            return e.what();
        }
        ADD_FAILURE() << "no InputError for:\n" << coupling;
        return "";
    }

    static std::string edited(const std::string& from, const std::string& to)
    {
        std::string text = hydrostaticText;
        const std::size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    }

    std::filesystem::path dir_;
};

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) \
        << "'" << (text) << "' does not contain '" << (part) << "'"

} // namespace


TEST_F(WaterPropertiesFiles, ReadsHydrostatic)
{
    write("couplingProperties", hydrostaticText);
    write("g", gravityText);
    const WaterProperties w = WaterProperties::readCase(dir_.string());
    EXPECT_EQ(w.level, WaterLevel::hydrostatic);
    EXPECT_EQ(w.hydrostatic.surfaceLevel, 0.45);
    EXPECT_EQ(w.hydrostatic.density, 1000.0);
    EXPECT_EQ(w.hydrostatic.viscosity, 1.79e-3);
    EXPECT_EQ(w.hydrostatic.addedMassCoefficient, 0.5);
    EXPECT_TRUE(w.hydrostatic.drag);
    EXPECT_EQ(w.hydrostatic.gravity, 9.81);
    EXPECT_EQ(w.gravity, Vec3(0, 0, -9.81));
}


TEST_F(WaterPropertiesFiles, OptionalEntriesAndOtherLevels)
{
    write("couplingProperties", edited("    addedMassCoefficient  0.5;\n    drag                  SchillerNaumann;\n",
                                       "    drag none;\n"));
    write("g", "value (0 0 -3.7);\n");
    WaterProperties w = WaterProperties::readCase(dir_.string());
    EXPECT_EQ(w.hydrostatic.addedMassCoefficient, 0.5);
    EXPECT_FALSE(w.hydrostatic.drag);
    EXPECT_EQ(w.hydrostatic.gravity, 3.7);

    // none needs no hydrostatic dictionary; cfd leaves its own entries to OpenFOAM.
    std::filesystem::remove(dir_ / "constant" / "g");
    write("couplingProperties", header + "waterLevel none;\n");
    EXPECT_EQ(WaterProperties::readCase(dir_.string()).level, WaterLevel::none);
    write("couplingProperties", header + "waterLevel cfd;\ncfd { dragModel DiFelice; }\n");
    EXPECT_EQ(WaterProperties::readCase(dir_.string()).level, WaterLevel::cfd);
}


TEST_F(WaterPropertiesFiles, BadInputIsRefusedNamingFileEntryAndAllowed)
{
    std::string e = errorOf(edited("waterLevel hydrostatic;", "waterLevel hydrostatc;"));
    EXPECT_CONTAINS(e, "couplingProperties");
    EXPECT_CONTAINS(e, "waterLevel");
    EXPECT_CONTAINS(e, "none");
    EXPECT_CONTAINS(e, "cfd");

    e = errorOf(edited("rho                   1000;", "rho -1000;"));
    EXPECT_CONTAINS(e, "hydrostatic.rho");
    EXPECT_CONTAINS(e, "positive");

    e = errorOf(edited("mu                    1.79e-3;", "mu 0;"));
    EXPECT_CONTAINS(e, "hydrostatic.mu");

    e = errorOf(edited("mu                    1.79e-3;", ""));
    EXPECT_CONTAINS(e, "hydrostatic.mu");
    EXPECT_CONTAINS(e, "missing");

    e = errorOf(edited("addedMassCoefficient  0.5;", "addedMassCoefficient -0.5;"));
    EXPECT_CONTAINS(e, "hydrostatic.addedMassCoefficient");

    e = errorOf(edited("drag                  SchillerNaumann;", "drag Stokes;"));
    EXPECT_CONTAINS(e, "hydrostatic.drag");
    EXPECT_CONTAINS(e, "SchillerNaumann");

    e = errorOf(edited("surfaceLevel          0.45;", "surfaceLevell 0.45;"));
    EXPECT_CONTAINS(e, "surfaceLevell");

    e = errorOf(edited("surfaceLevel          0.45;", "surfaceLevel high;"));
    EXPECT_CONTAINS(e, "hydrostatic.surfaceLevel");

    // `floating` only where the scene asked for it (the ridge sets the level itself).
    e = errorOf(edited("surfaceLevel          0.45;", "surfaceLevel floating;"));
    EXPECT_CONTAINS(e, "hydrostatic.surfaceLevel");
    EXPECT_CONTAINS(e, "ridgeDEM");
    write("couplingProperties", edited("surfaceLevel          0.45;", "surfaceLevel floating;"));
    EXPECT_TRUE(WaterProperties::readCase(dir_.string(), true).hydrostatic.floatingSurface);

    e = errorOf(header + "waterLevel hydrostatic;\n");
    EXPECT_CONTAINS(e, "'hydrostatic'");
    EXPECT_CONTAINS(e, "missing");

    e = errorOf(hydrostaticText, "value (0 -9.81 0);\n");
    EXPECT_CONTAINS(e, "constant/g");
    EXPECT_CONTAINS(e, "-z");

    // No constant/g at all.
    write("couplingProperties", hydrostaticText);
    EXPECT_THROW(WaterProperties::read((dir_ / "constant" / "couplingProperties").string(), ""), InputError);
}
