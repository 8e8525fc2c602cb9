#include "IceBlocks.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

using namespace iceDEM;

namespace
{

double minimumSpacing(const std::vector<Vec3>& c)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < c.size(); ++a)
        for (std::size_t b = a + 1; b < c.size(); ++b)
            best = std::min(best, (c[a] - c[b]).norm());
    return best;
}

std::string writeTemp(const std::string& name, const std::string& text)
{
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    std::ofstream(path) << text;
    return path;
}

} // namespace


TEST(PlanPolygon, RectangleAreaCentroidAndClip)
{
    const PlanPolygon r = PlanPolygon::rectangle(0.4, 0.2);
    EXPECT_NEAR(r.area(), 0.08, 1e-15);
    EXPECT_NEAR(r.centroid().x(), 0.2, 1e-15);
    EXPECT_NEAR(r.centroid().y(), 0.1, 1e-15);
    EXPECT_NEAR(r.aspectRatio(), 2.0, 1e-12);
    // Cut off the triangle beyond the diagonal x + y > 0.4.
    const PlanPolygon cut = r.clipped(Vec2(0.4, 0.0), Vec2(1, 1).normalized());
    EXPECT_NEAR(cut.area(), 0.08 - 0.5*0.2*0.2, 1e-15);
    EXPECT_TRUE(cut.contains(Vec2(0.1, 0.1)));
    EXPECT_FALSE(cut.contains(Vec2(0.39, 0.19)));
}


TEST(IceBlocks, HcpSpacingAndThickness)
{
    const double d = 0.055;
    const std::vector<Vec3> c = hcpBlockCentres(PlanPolygon::rectangle(0.4, 0.3), d, 2);
    // Close packing: nearest neighbours exactly one diameter apart, in a layer and across layers.
    EXPECT_NEAR(minimumSpacing(c), d, 1e-12);
    double zMin = 1e9, zMax = -1e9;
    int across = 0;
    for (const Vec3& p : c)
    {
        zMin = std::min(zMin, p.z());
        zMax = std::max(zMax, p.z());
    }
    for (const Vec3& a : c)
        for (const Vec3& b : c)
            if (a.z() < b.z() && std::abs((a - b).norm() - d) < 1e-12) ++across;
    EXPECT_GT(across, 0);
    // Two layers of 55 mm spheres: a 0.10 m block (d + d sqrt(2/3) = 0.0999 m).
    EXPECT_NEAR(zMax - zMin + d, hcpThickness(d, 2), 1e-12);
    EXPECT_NEAR(hcpThickness(d, 2), 0.0999, 1e-4);
}


TEST(IceBlocks, SphereCountMatchesPlanAreaPerLayer)
{
    // Each sphere stands for one lattice cell: count * cell area = plan area,
    // up to the cells cut by the outline (about perimeter / (2 d) per layer).
    const double d = 0.055;
    for (double length : {0.25, 0.4, 1.0})
    {
        const PlanPolygon outline = PlanPolygon::rectangle(length, 0.7*length);
        const auto c = hcpBlockCentres(outline, d, 2);
        const double represented = c.size()/2.0*hcpCellArea(d);
        const double boundaryCells = 2.0*(1.7*length)/d;
        EXPECT_NEAR(represented, outline.area(), boundaryCells*hcpCellArea(d)/2.0) << length;
        for (const Vec3& p : c)
        {
            EXPECT_TRUE(outline.contains(p.head<2>()));
        }
    }
}


TEST(IceBlocks, EmpiricalOutlineMatchesTargetArea)
{
    std::mt19937_64 rng(7);
    const BlockSize size{0.35, 0.25, 0.07};
    for (int k = 0; k < 20; ++k)
    {
        const PlanPolygon p = blockOutline(size, BlockShape::empirical, rng);
        EXPECT_NEAR(p.area(), size.planArea, 1e-9*size.planArea);
        EXPECT_NEAR(p.centroid().norm(), 0.0, 1e-12);
        EXPECT_LE(p.extent(Vec2(1, 0)), size.length + 1e-12);
        EXPECT_LE(p.extent(Vec2(0, 1)), size.width + 1e-12);
        EXPECT_GE(p.vertices().size(), 5u);   // at least one cut
    }
    const PlanPolygon cuboid = blockOutline(size, BlockShape::cuboid, rng);
    EXPECT_NEAR(cuboid.area(), 0.35*0.25, 1e-15);
}


TEST(IceBlocks, SyntheticSizesHaveMeanAspectRatio1p4)
{
    const BlockSizeSource source = BlockSizeSource::synthetic({});
    std::mt19937_64 rng(3);
    double sumAspect = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k)
    {
        const BlockSize b = source.draw(rng);
        ASSERT_GE(b.length, b.width);
        ASSERT_LE(b.planArea, b.length*b.width);
        ASSERT_GE(b.width, 0.12);
        sumAspect += b.length/b.width;
    }
    EXPECT_NEAR(sumAspect/n, 1.4, 0.01);
}


TEST(IceBlocks, CsvSizesReadAndValidated)
{
    const std::string good = writeTemp("blocks_good.csv",
        "# measured blocks\nlength_m,width_m,plan_area_m2\n0.30,0.20,0.05\n0.25,0.25,0.06\n");
    const BlockSizeSource s = BlockSizeSource::fromCsv(good);
    ASSERT_EQ(s.rows().size(), 2u);
    EXPECT_DOUBLE_EQ(s.rows()[1].planArea, 0.06);

    const std::string tooBig = writeTemp("blocks_bad.csv", "length_m,width_m,plan_area_m2\n0.30,0.20,0.07\n");
    try
    {
        BlockSizeSource::fromCsv(tooBig);
        FAIL() << "plan area above length * width accepted";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), tooBig);
        EXPECT_EQ(e.entry(), "line 2");
    }
    EXPECT_THROW(BlockSizeSource::fromCsv(writeTemp("blocks_hdr.csv", "a,b,c\n1,1,1\n")), InputError);
    EXPECT_THROW(BlockSizeSource::fromCsv("/nonexistent/blocks.csv"), InputError);
}
