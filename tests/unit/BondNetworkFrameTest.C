#include "BondNetworkFrame.H"

#include <gtest/gtest.h>

using namespace iceDEM;

namespace
{

//- Particles of tags 10, 20, 30 (radii 1, 3, 1): 20 has flown far away since its bond broke.
struct ThreeParticles
{
    ParticleFrame particles;
    std::map<long, std::size_t> indexOfTag{{10, 0}, {20, 1}, {30, 2}};

    ThreeParticles()
    {
        particles.position = {Vec3(0, 0, 0), Vec3(100, 0, 0), Vec3(2, 0, 0)};
        particles.radius = {1.0, 3.0, 1.0};
    }
};

} // namespace


TEST(BondNetworkFrame, IntactBondsJoinTheParticlesNow)
{
    const ThreeParticles p;
    BondNetworkFrame network(p.particles, p.indexOfTag);
    network.addIntact(10, 30, 1);
    network.addIntact(10, 99, 0);    // no particle 99: left out

    const BondFrame& f = network.frame();
    EXPECT_EQ(f.points, p.particles.position);
    ASSERT_EQ(f.ends.size(), 1u);
    EXPECT_EQ(f.ends[0], (std::array<long, 2>{0, 2}));
    EXPECT_EQ(f.family, std::vector<int>{1});
    EXPECT_EQ(f.state, std::vector<int>{0});
    EXPECT_EQ(f.mode, std::vector<int>{0});
    EXPECT_EQ(f.time, std::vector<double>{-1.0});
}


TEST(BondNetworkFrame, BrokenBondsStayWhereTheyBroke)
{
    const ThreeParticles p;
    BondNetworkFrame network(p.particles, p.indexOfTag);
    BreakEvent e;
    e.time = 0.5;
    e.tagA = 10;
    e.tagB = 20;
    e.separation = Vec3(4, 0, 0);       // A at (0, 5, 0), B at (4, 5, 0) when it broke
    e.position = Vec3(1, 5, 0);         // the centre divides it as the radii, 1 : 3
    e.family = BondFamily::freeze;
    e.mode = BreakMode::shear;
    network.addBroken(e);

    const BondFrame& f = network.frame();
    ASSERT_EQ(f.ends.size(), 1u);
    ASSERT_EQ(f.points.size(), 5u);
    EXPECT_EQ(f.ends[0], (std::array<long, 2>{3, 4}));
    EXPECT_EQ(f.points[3], Vec3(0, 5, 0));
    EXPECT_EQ(f.points[4], Vec3(4, 5, 0));
    EXPECT_EQ(f.state, std::vector<int>{1});
    EXPECT_EQ(f.family, std::vector<int>{static_cast<int>(BondFamily::freeze)});
    EXPECT_EQ(f.mode, std::vector<int>{static_cast<int>(BreakMode::shear)});
    EXPECT_EQ(f.time, std::vector<double>{0.5});

    // A particle not in the frame: the centre halves the bond.
    e.tagB = 99;
    network.addBroken(e);
    EXPECT_EQ(network.frame().points[5], Vec3(-1, 5, 0));
    EXPECT_EQ(network.frame().points[6], Vec3(3, 5, 0));
    EXPECT_NO_THROW(bondsVtp(network.frame(), VtkFormat::binary));
}
