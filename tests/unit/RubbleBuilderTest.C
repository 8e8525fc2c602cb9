#include "InputError.H"
#include "RubbleBuilder.H"
#include "SavedRubble.H"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

using namespace iceDEM;

namespace
{

RubbleSpec smallBox(BlockShape shape)
{
    RubbleSpec s;
    s.boxLength = 1.2;
    s.boxWidth = 0.6;
    s.iceVolume = 0.08;
    s.shape = shape;
    s.firstSheetBase = 0.5;
    s.seed = 5;
    return s;
}

} // namespace


TEST(RubbleBuilder, BlocksInsideTheBoxWithoutOverlapAndEnoughIce)
{
    for (BlockShape shape : {BlockShape::cuboid, BlockShape::empirical})
    {
        const RubbleSpec spec = smallBox(shape);
        const Rubble rubble = buildRubble(spec, BlockSizeSource::synthetic({}));
        EXPECT_GE(rubble.iceVolume, spec.iceVolume);
        EXPECT_LT(rubble.iceVolume - rubble.blocks.back().volume, spec.iceVolume);
        const double r = 0.5*spec.particleDiameter;
        double lowest = HUGE_VAL;
        for (const ParticleSpec& p : rubble.particles)
        {
            EXPECT_GE(p.position.x() - r, -1e-12);
            EXPECT_LE(p.position.x() + r, spec.boxLength + 1e-12);
            EXPECT_GE(p.position.y() - r, -1e-12);
            EXPECT_LE(p.position.y() + r, spec.boxWidth + 1e-12);
            lowest = std::min(lowest, p.position.z() - r);
        }
        EXPECT_NEAR(lowest, spec.firstSheetBase, 1e-12);
        // Spheres of different blocks never overlap; within a block they touch at d.
        for (std::size_t a = 0; a < rubble.particles.size(); ++a)
            for (std::size_t b = a + 1; b < rubble.particles.size(); ++b)
            {
                const double d = (rubble.particles[a].position - rubble.particles[b].position).norm();
                ASSERT_GE(d, spec.particleDiameter*(1 - 1e-9)) << a << " " << b;
            }
        // Block bookkeeping: ids, counts and volumes agree.
        std::size_t counted = 0;
        for (std::size_t k = 0; k < rubble.blocks.size(); ++k)
        {
            const BuiltBlock& b = rubble.blocks[k];
            for (int i = b.firstParticle; i < b.firstParticle + b.particleCount; ++i)
                EXPECT_EQ(rubble.particles[i].block, int(k));
            counted += b.particleCount;
            EXPECT_NEAR(b.volume, b.planArea*rubble.blockThickness, 1e-15);
        }
        EXPECT_EQ(counted, rubble.particles.size());
    }
}


TEST(RubbleBuilder, SameSeedSameRubble)
{
    const Rubble a = buildRubble(smallBox(BlockShape::empirical), BlockSizeSource::synthetic({}));
    const Rubble b = buildRubble(smallBox(BlockShape::empirical), BlockSizeSource::synthetic({}));
    ASSERT_EQ(a.particles.size(), b.particles.size());
    for (std::size_t k = 0; k < a.particles.size(); ++k)
        EXPECT_EQ(a.particles[k].position, b.particles[k].position);
}


TEST(SavedRubble, WriteAndReadBackBitForBit)
{
    SavedRubble s;
    s.time = 12.345678901234567;
    s.waterLevel = 0.8;
    s.description = "test rubble";
    for (int k = 0; k < 5; ++k)
    {
        SavedParticle p;
        p.position = Vec3(std::sqrt(2.0)*k, M_PI/(k + 1), -1.0/3.0);
        p.velocity = Vec3(1e-17*k, -0.1, 0.2);
        p.angularVelocity = Vec3(0.3, std::exp(1.0), k);
        p.radius = 0.0275;
        p.density = 917;
        p.block = k/2;
        p.type = 1 + (k == 4);
        s.particles.push_back(p);
    }
    BondState b;
    b.tagA = 1;
    b.tagB = 3;
    b.family = BondFamily::freeze;
    b.restLength = 0.0549999999;
    b.shearDisplacement = Vec3(1e-9, -2e-9, 1.0/7.0);
    b.twistAngle = -1e-5;
    b.bendingAngle = Vec3(1.0/3.0, 0, 2e-300);
    b.tensileStrength = 18.4e3;
    b.shearStrength = 56.2e3;
    s.bonds = {b, b};
    s.bonds[1].tagB = 5;
    s.bonds[1].family = BondFamily::ice;

    const std::string path = (std::filesystem::temp_directory_path() / "savedRubbleTest.h5").string();
    s.write(path);
    const SavedRubble r = SavedRubble::read(path);
    EXPECT_EQ(r.time, s.time);
    EXPECT_EQ(r.waterLevel, s.waterLevel);
    ASSERT_EQ(r.particles.size(), s.particles.size());
    ASSERT_EQ(r.bonds.size(), s.bonds.size());
    for (std::size_t k = 0; k < s.particles.size(); ++k) EXPECT_TRUE(r.particles[k] == s.particles[k]) << k;
    for (std::size_t k = 0; k < s.bonds.size(); ++k) EXPECT_TRUE(r.bonds[k] == s.bonds[k]) << k;
    EXPECT_THROW(SavedRubble::read("/nonexistent/rubble.h5"), std::runtime_error);
}


namespace
{

SavedRubble oneParticleRubble()
{
    SavedRubble s;
    SavedParticle p;
    p.radius = 0.01;
    p.density = 917.0;
    s.particles = {p};
    return s;
}

} // namespace


TEST(SavedRubble, KindAndProvenanceAreKeptAndAnotherKindIsRefused)
{
    SavedRubble s = oneParticleRubble();
    s.kind = SavedRubble::settledRubble;
    s.provenance = "constant/rubbleProperties/box.length = 1.6\n";
    const std::string path = (std::filesystem::temp_directory_path() / "savedRubbleKindTest.h5").string();
    s.write(path);
    const SavedRubble r = SavedRubble::read(path, SavedRubble::settledRubble);
    EXPECT_EQ(r.kind, s.kind);
    EXPECT_EQ(r.provenance, s.provenance);
    try
    {
        SavedRubble::read(path, SavedRubble::ridge);
        FAIL() << "a settled rubble was read as a ridge";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(std::string(e.what()).find("holds a settled rubble, where a ridge is needed"), std::string::npos)
            << e.what();
    }
}

TEST(SavedRubble, ContactModulusIsKeptAndUnrecordedIsNaN)
{
    SavedRubble s = oneParticleRubble();
    const std::string path = (std::filesystem::temp_directory_path() / "savedRubbleModulusTest.h5").string();
    s.write(path);
    EXPECT_TRUE(std::isnan(SavedRubble::read(path).contactYoungsModulus));
    s.contactYoungsModulus = 1.95e8;
    s.write(path);
    EXPECT_EQ(SavedRubble::read(path).contactYoungsModulus, 1.95e8);
}

TEST(SavedRubble, TruncatedAndForeignFilesAreInputErrorsNamingTheFile)
{
    const std::string dir = std::filesystem::temp_directory_path().string();
    const std::string truncated = dir + "/savedRubbleTruncated.h5";
    std::ofstream(truncated) << "\x89HDF\r\n";
    EXPECT_THROW(SavedRubble::read(truncated), InputError);
    const std::string text = dir + "/savedRubbleText.h5";
    std::ofstream(text) << "particles 3\n";
    try
    {
        SavedRubble::read(text);
        FAIL() << "a text file was read as a saved stage";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), text);
        EXPECT_NE(std::string(e.what()).find("not an HDF5 file"), std::string::npos) << e.what();
    }
}
