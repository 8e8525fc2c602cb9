#include "StlWriter.H"
#include "AtomicFile.H"

#include <Eigen/Geometry>

#include <cmath>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace iceDEM
{

namespace
{

constexpr double pi = 3.14159265358979323846;

void checkGeometry
(
    const Vec3& baseCentre,
    const Vec3& axis,
    double radius,
    double length,
    int segments,
    const std::string& solidName
)
{
    auto fail = [](const std::string& what)
    {
        throw std::invalid_argument("cylinder STL: " + what);
    };
    if (!baseCentre.allFinite())
    {
        fail("base centre is not finite");
    }
    if (!axis.allFinite() || !(axis.norm() > 1e-12))
    {
        fail("axis must be a finite non-zero vector");
    }
    if (!(std::isfinite(radius) && radius > 0.0))
    {
        fail("radius must be positive (got " + std::to_string(radius) + ")");
    }
    if (!(std::isfinite(length) && length > 0.0))
    {
        fail("length must be positive (got " + std::to_string(length) + ")");
    }
    if (segments < 3)
    {
        fail("at least 3 segments are needed (got " + std::to_string(segments) + ")");
    }
    if (solidName.find_first_of(" \t\r\n") != std::string::npos)
    {
        fail("solid name '" + solidName + "' must be a single word");
    }
}

//- Unit vectors e1, e2 with e1 x e2 = axis.
void perpendicularBasis(const Vec3& axis, Vec3& e1, Vec3& e2)
{
    int k;
    axis.cwiseAbs().minCoeff(&k);
    e1 = axis.cross(Vec3::Unit(k)).normalized();
    e2 = axis.cross(e1);
}

void writeFacet(std::ostream& out, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 n = (b - a).cross(c - a).normalized();
    out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n"
        << "    outer loop\n";
    for (const Vec3* v : {&a, &b, &c})
    {
        out << "      vertex " << v->x() << " " << v->y() << " " << v->z() << "\n";
    }
    out << "    endloop\n"
        << "  endfacet\n";
}

} // namespace


void writeCylinderStl
(
    const std::string& path,
    const Vec3& baseCentre,
    const Vec3& axis,
    double radius,
    double length,
    int segments,
    const std::string& solidName
)
{
    checkGeometry(baseCentre, axis, radius, length, segments, solidName);

    const Vec3 a = axis.normalized();
    Vec3 e1, e2;
    perpendicularBasis(a, e1, e2);
    const Vec3 topCentre = baseCentre + length*a;

    // Rings counter-clockwise about the axis, so the vertex orders below give outward normals.
    std::vector<Vec3> bottom(segments), top(segments);
    for (int k = 0; k < segments; ++k)
    {
        const double theta = 2.0*pi*k/segments;
        bottom[k] = baseCentre + radius*(std::cos(theta)*e1 + std::sin(theta)*e2);
        top[k] = bottom[k] + length*a;
    }

    writeStreamAtomically(path, [&](std::ostream& out)
    {
        out.precision(12);
        out << "solid " << solidName << "\n";
        for (int k = 0; k < segments; ++k)
        {
            const int next = (k + 1) % segments;
            writeFacet(out, bottom[k], bottom[next], top[next]);
            writeFacet(out, bottom[k], top[next], top[k]);
            writeFacet(out, topCentre, top[k], top[next]);
            writeFacet(out, baseCentre, bottom[next], bottom[k]);
        }
        out << "endsolid " << solidName << "\n";
    });
}

void writeBoxStl(const std::string& path, const Vec3& lo, const Vec3& hi, const std::string& solidName)
{
    if (!((hi - lo).array() > 0.0).all() || !lo.allFinite() || !hi.allFinite() || solidName.empty())
    {
        throw std::invalid_argument("writeBoxStl: the box needs hi > lo in every direction and a name");
    }
    auto corner = [&](int bits)
    {
        return Vec3(bits & 1 ? hi.x() : lo.x(), bits & 2 ? hi.y() : lo.y(), bits & 4 ? hi.z() : lo.z());
    };
    // Each face as four corners counter-clockwise seen from outside.
    const int faces[6][4] =
    {
        {0, 4, 6, 2}, {1, 3, 7, 5},     // x = lo, x = hi
        {0, 1, 5, 4}, {2, 6, 7, 3},     // y = lo, y = hi
        {0, 2, 3, 1}, {4, 5, 7, 6}      // z = lo, z = hi
    };
    writeStreamAtomically(path, [&](std::ostream& out)
    {
        out.precision(12);
        out << "solid " << solidName << "\n";
        for (const auto& f : faces)
        {
            writeFacet(out, corner(f[0]), corner(f[1]), corner(f[2]));
            writeFacet(out, corner(f[0]), corner(f[2]), corner(f[3]));
        }
        out << "endsolid " << solidName << "\n";
    });
}

} // namespace iceDEM
