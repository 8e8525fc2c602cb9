#include "StlWriter.H"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace iceDEM;

namespace
{

struct Facet
{
    Vec3 normal;
    Vec3 v[3];
};

struct StlSolid
{
    std::string name;
    std::string endName;
    std::vector<Facet> facets;
};

//- A strict reader of the ASCII STL grammar the writer produces.
StlSolid readAsciiStl(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
    {
        throw std::runtime_error("cannot open " + path);
    }
    auto expect = [&](const std::string& word)
    {
        std::string w;
        if (!(in >> w) || w != word)
        {
            throw std::runtime_error("expected '" + word + "', got '" + w + "'");
        }
    };
    auto readVec = [&]()
    {
        Vec3 v;
        if (!(in >> v.x() >> v.y() >> v.z()))
        {
            throw std::runtime_error("expected three numbers");
        }
        return v;
    };

    StlSolid solid;
    expect("solid");
    in >> solid.name;
    std::string word;
    while (in >> word && word == "facet")
    {
        Facet f;
        expect("normal");
        f.normal = readVec();
        expect("outer");
        expect("loop");
        for (Vec3& v : f.v)
        {
            expect("vertex");
            v = readVec();
        }
        expect("endloop");
        expect("endfacet");
        solid.facets.push_back(f);
    }
    if (word != "endsolid")
    {
        throw std::runtime_error("expected 'endsolid', got '" + word + "'");
    }
    in >> solid.endName;
    if (in >> word)
    {
        throw std::runtime_error("trailing text '" + word + "'");
    }
    return solid;
}

class StlWriter : public ::testing::Test
{
protected:
    void SetUp() override
    {
        const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path() / ("iceDEM_StlWriter_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    void TearDown() override
    {
        fs::remove_all(dir_);
    }

    std::string path(const std::string& relative) const
    {
        return (dir_/relative).string();
    }

    std::size_t nEntries() const
    {
        return std::distance(fs::directory_iterator(dir_), fs::directory_iterator());
    }

    //- Every check on one written cylinder.
    void checkCylinder(const Vec3& base, const Vec3& axisIn, double radius, double length, int segments)
    {
        const std::string file = path("cylinder.stl");
        writeCylinderStl(file, base, axisIn, radius, length, segments, "platen");
        const StlSolid solid = readAsciiStl(file);
        const Vec3 axis = axisIn.normalized();
        const Vec3 centre = base + 0.5*length*axis;
        const double eps = 1e-9*(radius + length);

        EXPECT_EQ(solid.name, "platen");
        EXPECT_EQ(solid.endName, "platen");
        ASSERT_EQ(solid.facets.size(), static_cast<std::size_t>(4*segments));

        double volume = 0.0;
        std::map<std::pair<std::string, std::string>, int> edges;
        auto key = [](const Vec3& v)
        {
            std::ostringstream os;
            os.precision(8);
            os << v.x() << "," << v.y() << "," << v.z();
            return os.str();
        };
        for (const Facet& f : solid.facets)
        {
            for (const Vec3& v : f.v)
            {
                const double along = (v - base).dot(axis);
                const double fromAxis = (v - base - along*axis).norm();
                EXPECT_TRUE(std::abs(along) < eps || std::abs(along - length) < eps) << along;
                EXPECT_TRUE(fromAxis < eps || std::abs(fromAxis - radius) < eps) << fromAxis;
            }
            const Vec3 cross = (f.v[1] - f.v[0]).cross(f.v[2] - f.v[0]);
            EXPECT_NEAR(f.normal.norm(), 1.0, 1e-9);
            EXPECT_GT(f.normal.dot(cross.normalized()), 1.0 - 1e-9);    // matches the vertex order
            const Vec3 centroid = (f.v[0] + f.v[1] + f.v[2])/3.0;
            EXPECT_GT(f.normal.dot(centroid - centre), 0.0);                   // outward
            volume += f.v[0].dot(f.v[1].cross(f.v[2]))/6.0;
            for (int k = 0; k < 3; ++k)
            {
                ++edges[{key(f.v[k]), key(f.v[(k + 1) % 3])}];
            }
        }
        // Closed and consistently oriented: every directed edge once, its reverse once.
        for (const auto& [edge, count] : edges)
        {
            EXPECT_EQ(count, 1);
            EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
        }
        const double polygonArea = 0.5*segments*radius*radius*std::sin(2.0*M_PI/segments);
        EXPECT_NEAR(volume, polygonArea*length, 1e-8*polygonArea*length);
        EXPECT_EQ(nEntries(), 1u);   // no temporary file left behind
    }

    fs::path dir_;
};

} // namespace


TEST_F(StlWriter, VerticalPlatenCylinder)
{
    checkCylinder(Vec3(1.45, -0.1, -0.02), Vec3(0.0, 0.0, 1.0), 0.075, 0.59, 48);
}


TEST_F(StlWriter, TiltedAxisIsNormalised)
{
    checkCylinder(Vec3(0.3, -2.0, 5.0), Vec3(1.0, -2.0, 0.5), 0.2, 1.7, 7);
}


TEST_F(StlWriter, FewestSegments)
{
    checkCylinder(Vec3::Zero(), Vec3(0.0, 1.0, 0.0), 1.0, 2.0, 3);
}


TEST_F(StlWriter, OverwritesAnExistingFile)
{
    const std::string file = path("platen.stl");
    writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.0, 8, "first");
    writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.0, 5, "second");
    const StlSolid solid = readAsciiStl(file);
    EXPECT_EQ(solid.name, "second");
    EXPECT_EQ(solid.facets.size(), 20u);
    EXPECT_EQ(nEntries(), 1u);
}


TEST_F(StlWriter, UnwritablePathNamesThePath)
{
    // A regular file where a folder should be.
    std::ofstream(path("notAFolder")) << "x";
    const std::string file = path("notAFolder/platen.stl");
    try
    {
        writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.0, 8, "platen");
        FAIL() << "writing under a regular file must fail";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
}


TEST_F(StlWriter, BadGeometryThrows)
{
    const std::string file = path("bad.stl");
    EXPECT_THROW(writeCylinderStl(file, Vec3::Zero(), Vec3::Zero(), 1.0, 1.0, 8, "p"), std::invalid_argument);
    EXPECT_THROW(writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 0.0, 1.0, 8, "p"), std::invalid_argument);
    EXPECT_THROW(writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, -1.0, 8, "p"), std::invalid_argument);
    EXPECT_THROW(writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.0, 2, "p"), std::invalid_argument);
    EXPECT_THROW(writeCylinderStl(file, Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.0, 8, "two words"), std::invalid_argument);
    EXPECT_EQ(nEntries(), 0u);
}


TEST_F(StlWriter, BoxIsClosedWithOutwardNormalsAndItsVolume)
{
    const Vec3 lo(1.4, -0.1, 0.9), hi(1.65, 1.04, 1.2);
    writeBoxStl(path("box.stl"), lo, hi, "platen");
    const StlSolid solid = readAsciiStl(path("box.stl"));
    ASSERT_EQ(solid.facets.size(), 12u);
    // Divergence theorem: sum over facets of (centroid . n) area / 3 is the volume;
    // it comes out negative if any normal points inwards.
    double volume = 0.0;
    const Vec3 centre = 0.5 * (lo + hi);
    for (const Facet& f : solid.facets)
    {
        const Vec3 n = (f.v[1] - f.v[0]).cross(f.v[2] - f.v[0]);
        EXPECT_NEAR(n.normalized().dot(f.normal), 1.0, 1e-9);
        EXPECT_GT(((f.v[0] + f.v[1] + f.v[2]) / 3.0 - centre).dot(n), 0.0);
        volume += f.v[0].dot(n) / 6.0;
    }
    EXPECT_NEAR(volume, (hi - lo).prod(), 1e-9);
    EXPECT_THROW(writeBoxStl(path("bad.stl"), hi, lo, "platen"), std::invalid_argument);
}
